"""Fixtures of the server tests: test apps on the store URL of ``tests/conftest.py`` and running servers."""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

from steakhouse_testing import ThreadServer


@pytest.fixture
def make_settings(db_url: str, tmp_path: Path) -> Callable[..., Any]:
    """Settings for a test app on ``db_url``: in-process robots, fast flushes, a known admin token, no join
    rate limit (tests join many participants from one address; the limit has its own tests)."""
    from server.settings import Settings

    def make(studies: list[Path], **overrides: Any) -> Settings:
        values: dict[str, Any] = {"database_url": db_url, "study_files": tuple(studies), "robot_workers": 0,
                                  "admin_token": "admin-secret", "flush_interval_s": 0.1,
                                  "static_dir": tmp_path / "no-static", "join_rate_per_minute": 0}
        values.update(overrides)
        return Settings(**values)

    return make


@pytest.fixture
def live_server(make_settings: Callable[..., Any]) -> Iterator[Callable[..., ThreadServer]]:
    """``live_server(studies, robot_factory=None, clock=None, pings=True, **settings)``: a started
    :class:`ThreadServer` (``clock``: the rounds' wall clock, e.g. a ``ManualClock``; ``pings``: see there), stopped
    at the end of the test."""
    from server.app import create_app

    started: list[ThreadServer] = []

    def start(studies: list[Path], robot_factory: Callable[..., Any] | None = None, clock: Any = None,
              pings: bool = True, **overrides: Any) -> ThreadServer:
        server = ThreadServer(create_app(make_settings(studies, **overrides), robot_factory=robot_factory,
                                         clock=clock), pings=pings)
        started.append(server.__enter__())
        return server

    yield start
    for server in reversed(started):
        server.__exit__(None, None, None)
