"""Scripted participants who game the engagement rules, sending exactly what the browser sends for them
(static/js/game/keys.js, controls.js): the other side of the validity rules' data (docs/protocol.md, "Taking part").

- ``hold_key``: holds "." (stay) down for the whole round. The browser sends one ``stay`` for the press and, on the
  fixed clock, one more per tick period while the key repeats; on the paper's clock a held key is one press.
- ``tap_key``: presses "." again and again (an auto-clicker, or a finger drumming), every ``tap_seconds``: each
  press is a ``stay``, on either clock.
- ``random_task``: every ``every_seconds`` clicks a task button at random among those that are enabled (the ones
  that fit what the cook holds; a disabled button sends nothing), whatever the kitchen shows.
- ``one_key``: presses one key (".") once per round and nothing else.

Each is a schedule (:meth:`Script.delay`) and what it sends when due (:meth:`Script.send`); the pilot's client runs it
on the wall clock (``pilot.client``), a test on its own clock.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from pilot.mind import fits
from planner.subtasks import SUBTASKS

ScriptKind = Literal["hold_key", "tap_key", "random_task", "one_key"]
SCRIPTS: tuple[ScriptKind, ...] = ("hold_key", "tap_key", "random_task", "one_key")
STAY: dict[str, Any] = {"type": "interrupt", "action": "stay"}


@dataclass(frozen=True, slots=True)
class Script:
    kind: ScriptKind
    every_seconds: float = 8.0
    """``random_task``: seconds between clicks."""
    tap_seconds: float = 0.2
    """``tap_key``: seconds between presses."""

    def delay(self, mode: str, tick_rate_hz: float, sent: int) -> float | None:
        """Seconds until the next message after ``sent`` messages this round (``None``: it sends nothing more):
        the first at once."""
        if sent == 0:
            return 0.0
        if self.kind == "hold_key":
            return 1.0 / tick_rate_hz if mode == "fixed_rate" else None
        if self.kind == "tap_key":
            return self.tap_seconds
        if self.kind == "random_task":
            return self.every_seconds
        return None

    def send(self, held: str | None, needs: Mapping[str, str], rng: np.random.Generator) -> dict[str, Any]:
        """The message the browser sends now (``held``: what the cook holds in the last frame)."""
        if self.kind != "random_task":
            return dict(STAY)
        enabled = [s for s in SUBTASKS if fits(s, held, needs)]
        return {"type": "select_subtask", "subtask": enabled[int(rng.integers(len(enabled)))].value}
