"""Fixtures and helpers of the admin dashboard's browser tests: a study server of its own (three small test
studies: one whose trial stays live, one that finishes fast, one with a practice round), scripted
participants over the websocket (one finishing a trial for the replay, one kept playing slowly in the
background for the live view), a page that tolerates the 401 / 404 answers the tests provoke on purpose,
and logging in.

Import the fixtures into a test module (``from steakhouse_admin import admin_server, admin_page``).
"""

from __future__ import annotations

import asyncio
import threading
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import httpx
import pytest
from steakhouse_browser import screenshot  # noqa: F401  (re-exported for the admin test modules)
from steakhouse_testing import Player, Socket, ThreadServer, next_subtask, play_to_end, write_study

REPO = Path(__file__).resolve().parents[2]
ADMIN_TOKEN = "dashboard-admin-secret"
CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
                 "--disable-sync", "--no-first-run"]
TIMEOUT_MS = 60_000
"""How long a browser test waits for a state before failing: generous, for a machine kept busy by other work
(a passing wait returns as soon as the state is reached)."""
LIVE_STUDY, REPLAY_STUDY, PRACTICE_STUDY = "dash_live", "dash_replay", "dash_practice"
REPLAY_FOV = 90
EXPECTED_CONSOLE = ("status of 401", "status of 404")
"""Chromium logs every failed fetch as a console error; these the tests cause on purpose."""


def write_studies(folder: Path) -> list[Path]:
    live = write_study(folder, LIVE_STUDY, title="Dashboard live study", kitchens=["none_3"],
                       robots=["fov_aware", "baseline"], timing={"tick_rate_hz": 8},
                       world={"orders": 20, "horizon": 6000, "kb_delay": 1},
                       # The live view's health warning is shown against the study's limit (the default, 5 %).
                       validity={"max_missed_decisions_pct": 5},
                       recruiting={"completion_code": "LIVE-OK", "url_parameters": ["PROLIFIC_PID", "STUDY_ID",
                                                                                    "SESSION_ID"]})
    replay = write_study(folder, REPLAY_STUDY, title="Dashboard replay study", kitchens=["practice"],
                         robots=["fov_aware", "stay"], timing={"tick_rate_hz": 30},
                         world={"orders": 1, "horizon": 500, "kb_delay": 1, "fov_angle": REPLAY_FOV},
                         recruiting={"completion_code": "DASH-OK-9",
                                     "completion_redirect_url": "https://recruit.example/complete?cc={code}"})
    practice = write_study(folder, PRACTICE_STUDY, title="Dashboard practice study", kitchens=["practice"],
                           robots=["stay"], practice=[{"kitchen": "practice", "robot": "stay", "count": 1}],
                           world={"orders": 1, "horizon": 500, "kb_delay": 1})
    return [live, replay, practice]


@dataclass
class AdminServer:
    thread: ThreadServer
    url: str
    admin: httpx.Client
    background: list[BackgroundPlayer] = field(default_factory=list)

    def get(self, path: str, **params: Any) -> Any:
        response = self.admin.get(path, params=params)
        response.raise_for_status()
        return response.json()

    def finished_trial(self, prolific_pid: str) -> tuple[str, int]:
        """A participant of the replay study who played their first main trial to the end and answered its
        questionnaire: (public id, trial id)."""

        async def scenario() -> tuple[str, int]:
            player = Player(self.url)
            try:  # closed on a failure too, else its socket is left for the next test to find unclosed
                joined = await player.join(REPLAY_STUDY, PROLIFIC_PID=prolific_pid)
                (await player.post("/api/session/consent", {"accept": True})).raise_for_status()
                (await player.post("/api/session/instructions_done")).raise_for_status()
                sock = await player.socket()
                hello = await sock.recv()
                await play_to_end(sock)
                await sock.close()
                (await player.post("/api/session/questionnaire", {"questionnaire_id": "q", "answers": {"a": 5}})
                 ).raise_for_status()
            finally:
                await player.close()
            return joined["participant_id"], int(hello["trial"]["id"])

        finished: tuple[str, int] = in_thread(scenario)
        return finished

    def live_trial(self, prolific_pid: str) -> BackgroundPlayer:
        player = BackgroundPlayer(self.url, prolific_pid)
        self.background.append(player.start())
        return player


def in_thread(scenario: Callable[[], Any]) -> Any:
    """``asyncio.run(scenario())`` in a thread of its own (Playwright's sync API owns this thread's loop)."""
    out: dict[str, Any] = {}

    def run() -> None:
        try:
            out["value"] = asyncio.run(scenario())
        except BaseException as exc:  # noqa: BLE001 - re-raised below
            out["error"] = exc

    thread = threading.Thread(target=run, name="scripted-participant", daemon=True)
    thread.start()
    thread.join(timeout=90)
    if "error" in out:
        raise out["error"]
    if "value" not in out:
        raise RuntimeError("the scripted participant did not finish within 90 s")
    return out["value"]


class BackgroundPlayer:
    """A participant of the live study playing in a thread (a subtask every ``pause_s`` when idle), until
    :meth:`stop`; its trial stays live meanwhile (20 orders, a long horizon)."""

    def __init__(self, url: str, prolific_pid: str, pause_s: float = 0.6) -> None:
        self.url, self.pid, self.pause_s = url, prolific_pid, pause_s
        self.trial_id: int | None = None
        self.participant_id: str | None = None
        self.ready = threading.Event()
        self.stopping = threading.Event()
        self.error: BaseException | None = None
        self.thread = threading.Thread(target=self._run, name=f"player-{prolific_pid}", daemon=True)

    def start(self) -> BackgroundPlayer:
        self.thread.start()
        if not self.ready.wait(30):
            raise RuntimeError(f"the background participant did not start: {self.error!r}")
        return self

    def stop(self) -> None:
        self.stopping.set()
        self.thread.join(timeout=15)

    def _run(self) -> None:
        try:
            asyncio.run(self._play())
        except BaseException as exc:  # noqa: BLE001 - reported by start() / the test
            self.error = exc
            self.ready.set()

    async def _play(self) -> None:
        player = Player(self.url)
        joined = await player.join(LIVE_STUDY, PROLIFIC_PID=self.pid)
        self.participant_id = joined["participant_id"]
        (await player.post("/api/session/consent", {"accept": True})).raise_for_status()
        (await player.post("/api/session/instructions_done")).raise_for_status()
        sock: Socket = await player.socket()
        hello = await sock.recv()
        self.trial_id = int(hello["trial"]["id"])
        self.ready.set()
        last_choice = 0.0
        while not self.stopping.is_set():
            try:
                message = await sock.recv(timeout=0.5)
            except TimeoutError:
                continue
            if message["type"] == "trial_end":
                break
            if message["type"] == "state" and time.monotonic() - last_choice > self.pause_s:
                choice = next_subtask(message)
                if choice is not None:
                    last_choice = time.monotonic()
                    await sock.send("select_subtask", subtask=choice)
        await sock.close()
        await player.close()


@pytest.fixture(scope="module")
def admin_server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[AdminServer]:
    from pydantic import SecretStr

    from server.app import create_app
    from server.settings import Settings

    folder = tmp_path_factory.mktemp("dashboard")
    settings = Settings(database_url=f"sqlite:///{folder / 'store.sqlite3'}", study_files=tuple(write_studies(folder)),
                        robot_workers=0, admin_token=SecretStr(ADMIN_TOKEN), flush_interval_s=0.1,
                        static_dir=REPO / "static", join_rate_per_minute=0)
    with ThreadServer(create_app(settings)) as thread:
        server = AdminServer(thread, thread.url, httpx.Client(base_url=thread.url, timeout=10,
                                                              headers={"Authorization": f"Bearer {ADMIN_TOKEN}"}))
        try:
            yield server
        finally:
            for player in server.background:
                player.stop()
            server.admin.close()


@pytest.fixture
def admin_page(browser: Any) -> Iterator[Callable[..., Any]]:
    """``admin_page(viewport=(1440, 900))``: a page in a fresh context (empty sessionStorage); fails the test on
    console errors and uncaught exceptions other than the failed fetches in ``EXPECTED_CONSOLE``."""
    contexts: list[tuple[Any, list[str]]] = []

    def make(viewport: tuple[int, int] = (1440, 900)) -> Any:
        context = browser.new_context(viewport={"width": viewport[0], "height": viewport[1]}, accept_downloads=True)
        page = context.new_page()
        problems: list[str] = []
        page.on("console", lambda msg: problems.append(f"console.{msg.type}: {msg.text}")
                if msg.type == "error" and not any(e in msg.text for e in EXPECTED_CONSOLE) else None)
        page.on("pageerror", lambda exc: problems.append(f"uncaught: {exc}"))
        page.set_default_timeout(TIMEOUT_MS)
        contexts.append((context, problems))
        return page

    yield make
    failures = [p for _, problems in contexts for p in problems]
    for context, _ in contexts:
        context.close()
    assert failures == [], failures


def login(page: Any, server: AdminServer, token: str = ADMIN_TOKEN, hash_: str = "") -> None:
    page.goto(f"{server.url}/admin/{hash_}")
    page.fill("#admin-token", token)
    page.click("#login-submit")
    page.wait_for_selector("#nav-studies")


def canvas_pixel(page: Any, selector: str, cell: tuple[int, int], fx: float = 0.5, fy: float = 0.5) -> tuple[int, ...]:
    """The RGB of the canvas at a point of ``cell`` (fractions of the cell from its top-left corner)."""
    return tuple(page.eval_on_selector(selector, """(canvas, [cx, cy, fx, fy]) => {
      const [w] = canvas.dataset.grid.split('x').map(Number);
      const size = canvas.width / w;
      const x = Math.floor((cx + fx) * size);
      const y = Math.floor((cy + fy) * size);
      const data = canvas.getContext('2d').getImageData(x, y, 1, 1).data;
      return [data[0], data[1], data[2]];
    }""", [cell[0], cell[1], fx, fy]))
