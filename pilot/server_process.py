"""The server a pilot runs against when no ``--url`` is given: ``steakhouse serve`` in a child process on
127.0.0.1 and a free port, with a random admin token (the pilot joins with it), no join limit, and stopped
(by its pid) when the pilot ends, however it ends."""

from __future__ import annotations

import os
import secrets
import socket
import subprocess
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import httpx

START_TIMEOUT_S = 120.0


@dataclass(frozen=True)
class RunningServer:
    url: str
    admin_token: str
    pid: int


def free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        port: int = s.getsockname()[1]
        return port


@contextmanager
def serve(study_file: Path, database_url: str, workers: int | None = None,
          log_file: Path | None = None) -> Iterator[RunningServer]:
    """Start the server for ``study_file`` on ``database_url``; stop it on leaving the block."""
    port, token = free_port(), secrets.token_urlsafe(24)
    env = {**os.environ, "STEAKHOUSE_ADMIN_TOKEN": token, "STEAKHOUSE_JOIN_RATE_PER_MINUTE": "0"}
    command = [sys.executable, "-m", "server.cli", "serve", "--host", "127.0.0.1", "--port", str(port),
               "--study", str(study_file), "--database-url", database_url, "--log-level", "warning"]
    if workers is not None:
        command += ["--workers", str(workers)]
    log = open(log_file, "ab") if log_file is not None else subprocess.DEVNULL  # noqa: SIM115
    process = subprocess.Popen(command, env=env, stdout=log, stderr=log)
    url = f"http://127.0.0.1:{port}"
    try:
        _wait_ready(url, process)
        yield RunningServer(url, token, process.pid)
    finally:
        process.terminate()
        try:
            process.wait(timeout=20)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()
        if log is not subprocess.DEVNULL:
            log.close()  # type: ignore[union-attr]


def _wait_ready(url: str, process: subprocess.Popen[bytes]) -> None:
    deadline = time.monotonic() + START_TIMEOUT_S
    # One client for the polls: httpx.get() builds a client, and loads a TLS context, for each one.
    with httpx.Client(timeout=2) as http:
        while time.monotonic() < deadline:
            if process.poll() is not None:
                raise RuntimeError(f"the server stopped at start (exit code {process.returncode}); see its log")
            try:
                if http.get(url + "/healthz").status_code == 200:
                    return
            except httpx.HTTPError:
                pass
            time.sleep(0.2)
    raise RuntimeError(f"the server did not answer within {START_TIMEOUT_S:.0f} s")
