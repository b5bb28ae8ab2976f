"""The pilot's progress: a one-line bar on a terminal (participants done, rounds running, ETA), plain lines
otherwise (one per finished participant)."""

from __future__ import annotations

import sys
import time
from typing import TextIO


class Progress:
    def __init__(self, total: int, label: str, stream: TextIO | None = None) -> None:
        self.total, self.label = total, label
        self.stream = stream or sys.stderr
        self.tty = self.stream.isatty()
        self.done = 0
        self.running = 0
        self.failed = 0
        self.started = time.monotonic()

    def eta(self) -> str:
        if not self.done:
            return "ETA –"
        left = (time.monotonic() - self.started) / self.done * (self.total - self.done)
        return f"ETA {int(left // 60)}:{int(left % 60):02d}"

    def rounds(self, delta: int) -> None:
        self.running += delta
        if self.tty:
            self.draw()

    def finished(self, name: str, ok: bool, note: str = "") -> None:
        self.done += 1
        self.failed += not ok
        if self.tty:
            self.draw()
        else:
            elapsed = time.monotonic() - self.started
            status = "done" if ok else f"FAILED: {note}"
            print(f"{self.label} {self.done}/{self.total} {name} {status} ({elapsed:.0f} s)", file=self.stream,
                  flush=True)

    def advance(self, steps: int = 1) -> None:
        """``steps`` more units done, without a line of their own (the bar is redrawn on a terminal)."""
        self.done += steps
        if self.tty:
            self.draw()

    def draw(self) -> None:
        width = 30
        filled = int(width * self.done / max(self.total, 1))
        bar = "#" * filled + "-" * (width - filled)
        failed = f", {self.failed} failed" if self.failed else ""
        self.stream.write(f"\r{self.label} [{bar}] {self.done}/{self.total} done, {self.running} rounds running"
                          f"{failed}, {self.eta()}   ")
        self.stream.flush()

    def close(self) -> None:
        if self.tty:
            self.stream.write("\n")
            self.stream.flush()
