"""The browser tests' study server as the tests see it: its admin token, the repository root, and
:class:`StudyServer`, the running server with helpers to read what the store holds. A module of its own (not
``conftest``) so that test files import it by a name no other folder's module has.

Importable from the test files because ``tests/static/conftest.py`` puts this folder on ``sys.path``.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import httpx
from steakhouse_testing import ThreadServer

REPO = Path(__file__).resolve().parents[2]
ADMIN_TOKEN = "browser-admin-secret"


class StudyServer:
    """The running server, with helpers to read what the store holds (admin API and store queries)."""

    def __init__(self, thread: ThreadServer) -> None:
        self.thread = thread
        self.url = thread.url
        self.admin = httpx.Client(base_url=thread.url, headers={"Authorization": f"Bearer {ADMIN_TOKEN}"},
                                  timeout=10)

    @property
    def services(self) -> Any:
        return self.thread.services

    def link(self, study: str = "browser_flow", **params: str) -> str:
        query = "&".join(f"{k}={v}" for k, v in {"study": study, **params}.items())
        return f"{self.url}/?{query}"

    def get(self, path: str, **params: Any) -> Any:
        response = self.admin.get(path, params=params)
        response.raise_for_status()
        return response.json()

    def participant(self, public_id: str) -> dict[str, Any]:
        found: list[dict[str, Any]] = [p for p in self.get("/api/admin/participants") if p["participant_id"] == public_id]
        assert len(found) == 1, found
        return found[0]

    def trials(self, public_id: str) -> list[dict[str, Any]]:
        return list(self.get("/api/admin/trials", participant_id=public_id))

    def live(self, trial_id: int) -> dict[str, Any]:
        return dict(self.get(f"/api/admin/live/{trial_id}"))

    def events(self, trial_id: int, until: Callable[[list[str]], bool] | None = None,
               timeout: float = 10.0) -> list[dict[str, Any]]:
        """The trial's stored events; with ``until``, asked again (events reach the store in batches) until
        ``until(kinds)`` holds or ``timeout`` seconds pass."""
        end = time.monotonic() + timeout
        while True:
            events = list(self.get(f"/api/admin/trials/{trial_id}/events"))
            if until is None or until([e["kind"] for e in events]) or time.monotonic() > end:
                return events
            time.sleep(0.05)
