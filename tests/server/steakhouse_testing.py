"""Helpers for the server tests: study files, real servers (in a thread or in a process), a scripted
participant speaking the REST API and the websocket protocol.

Importable from the test files because ``tests/server/conftest.py`` puts this folder on ``sys.path``
(spawned robot worker processes inherit it, so test robot factories live next door).
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import os
import signal
import socket
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import IO, Any

import httpx
import uvicorn
import yaml
from websockets.asyncio.client import ClientConnection, connect
from websockets.exceptions import ConnectionClosedOK

from study_config.study.validity import DEFAULT_MAX_IDLE_PCT, DEFAULT_MAX_REFUSED_TASK_PCT, DEFAULT_MIN_TASK_STEP_PCT

REPO = Path(__file__).resolve().parents[2]
RECV_TIMEOUT = 10.0
# One TLS context for every test client: httpx otherwise loads the certificate bundle for each new client.
TLS = httpx.create_ssl_context()


def _merge(base: dict[str, Any], extra: dict[str, Any]) -> dict[str, Any]:
    out = dict(base)
    for key, value in extra.items():
        out[key] = _merge(out[key], value) if isinstance(value, dict) and isinstance(out.get(key), dict) else value
    return out


ENGAGEMENT_RULES: dict[str, float] = {"min_task_step_pct": DEFAULT_MIN_TASK_STEP_PCT,
                                      "max_refused_task_pct": DEFAULT_MAX_REFUSED_TASK_PCT,
                                      "max_idle_pct": DEFAULT_MAX_IDLE_PCT}
"""The engagement rules as a study gets them by default, for the tests that judge participants by them
(:func:`write_study` sets them aside)."""


def write_study(folder: Path, study_id: str = "tiny", **overrides: Any) -> Path:
    """A small study: one kitchen (``practice``), the ``stay`` robot, one order, 30 Hz, one questionnaire."""
    data: dict[str, Any] = {
        "id": study_id, "title": "Test study", "kitchens": ["practice"], "robots": ["stay"], "factors": ["robot"],
        "timing": {"mode": "fixed_rate", "tick_rate_hz": 30}, "world": {"orders": 1, "horizon": 300, "kb_delay": 1},
        "questionnaires": [{"id": "q", "items": [
            {"id": "a", "text": "A", "scale": {"min": 1, "max": 5}},
            {"id": "b", "text": "B", "scale": {"min": 1, "max": 5}, "required": False}]}],
        "reconnect": {"grace_seconds": 60},
        # Robot health is judged on the wall clock, and these tests' robots decide at 30 Hz on a machine shared by
        # parallel test workers: a test not about health must not fail because one decision of a few was late.
        # The health tests set their own threshold (tests/server/test_play_health.py).
        # The engagement rules judge the participant, and these tests' participants are scripts that answer each
        # state as it comes: on a loaded machine they read states a few ticks old and choose tasks that the world has
        # moved past (refused), or make too few of a short round's steps. A test not about engagement must not fail
        # for that; the engagement tests set the rules they test (tests/server/test_play_gaming.py and others).
        "validity": {"max_missed_decisions_pct": 100, "min_task_step_pct": 0, "max_refused_task_pct": 100,
                     "max_idle_pct": 100},
    }
    path = folder / f"{study_id}.yaml"
    path.write_text(yaml.safe_dump(_merge(data, overrides)), encoding="utf-8")
    return path


def eventually(read: Callable[[], Any], holds: Callable[[Any], bool], timeout: float = 10.0) -> Any:
    """``read()`` again until ``holds`` it or ``timeout`` seconds pass; returns the last value read (rows
    reach the store in batches, so what a test just caused may take a flush interval to appear)."""
    end = time.monotonic() + timeout
    value = read()
    while not holds(value) and time.monotonic() < end:
        time.sleep(0.05)
        value = read()
    return value


def wait_stored(where: Any, through: dict[int, int], timeout: float = 60.0) -> None:
    """Wait until the store (a ``Store`` or a database URL) holds, for each trial id in ``through``, its ticks
    up to the given one. The writer commits in batches: a test about what was stored waits for that state
    rather than sleeping for a flush interval, which a loaded machine can stretch. Fails after ``timeout``."""
    from sqlalchemy import func, select

    from store.engine import Store
    from store.tables import TickRow

    store = Store(where) if isinstance(where, str) else where
    try:
        def highest() -> dict[int, int]:
            with store.transaction() as session:
                rows = session.execute(select(TickRow.trial_id, func.max(TickRow.tick))
                                       .where(TickRow.trial_id.in_(list(through))).group_by(TickRow.trial_id))
                return dict(rows.all())

        seen = eventually(highest, lambda got: all(got.get(t, 0) >= n for t, n in through.items()), timeout)
        missing = {t: (seen.get(t, 0), n) for t, n in through.items() if seen.get(t, 0) < n}
        assert not missing, f"ticks not stored after {timeout} s (trial: (stored, wanted)): {missing}"
    finally:
        if store is not where:
            store.dispose()


def signed_test_code(study_id: str = "tiny", admin_token: str = "admin-secret", days: int = 1) -> str:
    """The code of an admin's test-run link for ``study_id`` (``server.admin.test_links``), valid ``days``."""
    from server.admin.test_links import make_test_code, signing_key

    return make_test_code(signing_key(admin_token), study_id, int(time.time()) + days * 86_400)


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


class PortTaken(RuntimeError):
    """Another process listens on the port a :class:`ProcessServer` was given (free when chosen)."""


def listening_pids(port: int) -> set[int]:
    """The processes with a TCP socket listening on ``port`` (Linux: ``/proc/net/tcp*`` and each process's open
    sockets; processes this one may not read are left out)."""
    inodes: set[str] = set()
    for table in ("/proc/net/tcp", "/proc/net/tcp6"):
        with contextlib.suppress(OSError), open(table) as rows:
            for row in list(rows)[1:]:
                fields = row.split()
                if fields[3] == "0A" and int(fields[1].rsplit(":", 1)[1], 16) == port:  # 0A: LISTEN
                    inodes.add(fields[9])
    pids: set[int] = set()
    if not inodes:
        return pids
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        with contextlib.suppress(OSError):
            for fd in os.listdir(f"/proc/{entry}/fd"):
                with contextlib.suppress(OSError):
                    link = os.readlink(f"/proc/{entry}/fd/{fd}")
                    if link.startswith("socket:[") and link[8:-1] in inodes:
                        pids.add(int(entry))
                        break
    return pids


class ThreadServer:
    """The app on a real uvicorn server in a background thread of this process (a real TCP socket).

    ``pings``: the server pings its websockets every 20 s, as ``steakhouse serve`` does. A Hypothesis test turns
    that off: the ping's payload comes from the ``random`` module, and Hypothesis fails a draw during which anything
    in the process, this server's thread included, used that module."""

    def __init__(self, app: Any, *, pings: bool = True) -> None:
        self.app = app
        self.server = uvicorn.Server(uvicorn.Config(app, host="127.0.0.1", port=0, log_level="warning",
                                                    ws_max_size=1 << 20, lifespan="on",
                                                    ws_ping_interval=20.0 if pings else None))
        self.thread = threading.Thread(target=self.server.run, name="test-server", daemon=True)

    def __enter__(self) -> ThreadServer:
        self.thread.start()
        deadline = time.monotonic() + 30
        while not self.server.started:
            if not self.thread.is_alive() or time.monotonic() > deadline:
                raise RuntimeError("the test server did not start")
            time.sleep(0.02)
        port = self.server.servers[0].sockets[0].getsockname()[1]
        self.url = f"http://127.0.0.1:{port}"
        return self

    def __exit__(self, *exc: Any) -> None:
        self.server.should_exit = True
        self.thread.join(timeout=30)

    @property
    def services(self) -> Any:
        return self.app.state.services


class ProcessServer:
    """``steakhouse serve`` in a child process (for SIGKILL and multi-process tests)."""

    def __init__(self, *, study: Path, database_url: str, workers: int = 1, env: dict[str, str] | None = None,
                 log: Path | None = None, log_level: str = "warning") -> None:
        self.database_url = database_url
        self._serve = ["--study", str(study), "--database-url", database_url, "--workers", str(workers),
                       "--log-level", log_level]
        self.port = free_port()
        self.env = {**os.environ, "STEAKHOUSE_ADMIN_TOKEN": "admin-secret", "STEAKHOUSE_FLUSH_INTERVAL_S": "0.2",
                    "STEAKHOUSE_JOIN_RATE_PER_MINUTE": "0", **(env or {})}
        self.env["PYTHONPATH"] = os.pathsep.join([str(REPO), str(Path(__file__).parent)])
        self.log = log
        self.process: subprocess.Popen[bytes] | None = None
        self._out: IO[bytes] | int | None = None  # the log file while running, or subprocess.DEVNULL

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def start(self) -> ProcessServer:
        """Launch and wait until ready; on a port another process took meanwhile (:class:`PortTaken`), again on
        another free port."""
        for _ in range(3):
            try:
                return self.launch().wait_ready()
            except PortTaken:
                self.kill()
                self.port = free_port()
        raise RuntimeError("three free ports in a row were taken before the server could bind one")

    def launch(self) -> ProcessServer:
        """Start the process without waiting (several servers can start side by side)."""
        out = open(self.log, "ab") if self.log else subprocess.DEVNULL  # noqa: SIM115 - closed in stop()
        self._out = out
        args = [sys.executable, "-m", "server.cli", "serve", "--port", str(self.port), *self._serve]
        self.process = subprocess.Popen(args, cwd=REPO, env=self.env, stdout=out, stderr=out)
        return self

    def wait_ready(self) -> ProcessServer:
        assert self.process is not None
        deadline = time.monotonic() + 60
        # One client for the polls: httpx.get() would build a new client, TLS context included, for each.
        with httpx.Client(timeout=1, verify=TLS) as http:
            while time.monotonic() < deadline:
                if self.process.poll() is not None:
                    if listening_pids(self.port):
                        raise PortTaken(self.port)
                    raise RuntimeError(f"server exited with {self.process.returncode}")
                try:
                    # Another test's server may answer on this port (it took the port between free_port() and
                    # this server's bind): ready only once this process is the one listening.
                    if (http.get(self.url + "/healthz").status_code == 200
                            and self.process.pid in listening_pids(self.port)):
                        return self
                except httpx.HTTPError:
                    pass
                time.sleep(0.05)
        if listening_pids(self.port) - {self.process.pid}:
            raise PortTaken(self.port)
        raise RuntimeError("server did not become healthy")

    def kill(self) -> None:
        """SIGKILL: no shutdown code runs, like a crash."""
        if self.process is not None and self.process.poll() is None:
            os.kill(self.process.pid, signal.SIGKILL)
            self.process.wait(timeout=10)
        self._close()

    def stop(self) -> None:
        if self.process is not None and self.process.poll() is None:
            self.process.send_signal(signal.SIGTERM)
            try:
                self.process.wait(timeout=15)
            except subprocess.TimeoutExpired:
                os.kill(self.process.pid, signal.SIGKILL)
                self.process.wait(timeout=10)
        self._close()

    def _close(self) -> None:
        out = getattr(self, "_out", None)
        if out is not None and out is not subprocess.DEVNULL:
            out.close()
        self._out = None


def condition_order(services: Any, public_id: str) -> list[str]:
    """The participant's condition order as the store has it (the participant's own answers never carry it:
    they are blind to their conditions)."""
    from store import participants

    with services.store.transaction() as session:
        row = participants.by_public_id(session, public_id)
        found = participants.assignment_of(session, row.id) if row is not None else None
        return list(found.condition_order) if found is not None else []


def http_client(base_url: str, **kwargs: Any) -> httpx.AsyncClient:
    """The tests' HTTP client. It drops idle connections after 1 s, well before uvicorn closes them (its keep-alive
    is 5 s): with both at 5 s, a request sent on a connection the server is closing at that moment fails with
    ReadError."""
    return httpx.AsyncClient(base_url=base_url, timeout=30, verify=TLS, limits=httpx.Limits(keepalive_expiry=1.0),
                             **kwargs)


class Player:
    """A participant: the REST calls of the flow, then websockets to play."""

    def __init__(self, base_url: str) -> None:
        self.base = base_url
        self.http = http_client(base_url)
        self.token = ""

    async def close(self) -> None:
        await self.http.aclose()

    @property
    def headers(self) -> dict[str, str]:
        return {"Authorization": f"Bearer {self.token}"}

    async def join(self, study_id: str = "tiny", **recruiting: str) -> dict[str, Any]:
        response = await self.http.post(f"/api/studies/{study_id}/join", json={"recruiting": recruiting})
        response.raise_for_status()
        body: dict[str, Any] = response.json()
        self.token = body["token"]
        return body

    async def post(self, path: str, body: Any = None) -> httpx.Response:
        return await self.http.post(path, json=body, headers=self.headers)

    async def session(self) -> dict[str, Any]:
        response = await self.http.get("/api/session", headers=self.headers)
        response.raise_for_status()
        return response.json()  # type: ignore[no-any-return]

    async def ready(self, study_id: str = "tiny", **recruiting: str) -> None:
        """Join, consent and read the instructions: the next step is a trial."""
        await self.join(study_id, **recruiting)
        (await self.post("/api/session/consent", {"accept": True})).raise_for_status()
        (await self.post("/api/session/instructions_done")).raise_for_status()

    async def socket(self) -> Socket:
        return await Socket.open(self.base.replace("http", "ws", 1) + f"/ws/play?token={self.token}")


class Socket:
    """A websocket speaking protocol v1: numbered sends, a log of everything received."""

    def __init__(self, ws: ClientConnection) -> None:
        self.ws = ws
        self.seq = 0
        self.received: list[dict[str, Any]] = []

    @classmethod
    async def open(cls, url: str) -> Socket:
        # Like a browser, read every frame as it comes (no flow control on the receiving side).
        return cls(await connect(url, max_size=1 << 22, max_queue=None))

    async def send(self, type_: str, **fields: Any) -> int:
        self.seq += 1
        await self.ws.send(json.dumps({"v": 1, "seq": self.seq, "type": type_, **fields}))
        return self.seq

    async def send_raw(self, text: str | bytes) -> None:
        await self.ws.send(text)

    async def recv(self, timeout: float = RECV_TIMEOUT) -> dict[str, Any]:
        message: dict[str, Any] = json.loads(await asyncio.wait_for(self.ws.recv(), timeout))
        self.received.append(message)
        return message

    async def until(self, predicate: Callable[[dict[str, Any]], bool], timeout: float = RECV_TIMEOUT) -> dict[str, Any]:
        deadline = time.monotonic() + timeout
        while True:
            message = await self.recv(max(deadline - time.monotonic(), 0.01))
            if predicate(message):
                return message

    async def close(self) -> None:
        await self.ws.close()


def next_subtask(state: dict[str, Any]) -> str | None:
    """A scripted participant's choice: when idle, the first subtask the model considers available."""
    over = state["hud"]["orders_left"] == 0 or state["hud"]["ticks_left"] == 0
    if state["subtask"] is None and state["available"] and not over:
        return str(state["available"][0])
    return None


async def play_to_end(sock: Socket, *, on_state: Callable[[dict[str, Any]], Any] | None = None,
                      timeout: float = 60.0) -> dict[str, Any]:
    """Play by choosing subtasks until ``trial_end``; returns it."""
    deadline = time.monotonic() + timeout
    while True:
        message = await sock.recv(max(deadline - time.monotonic(), 0.01))
        if message["type"] == "trial_end":
            return message
        if message["type"] == "state":
            if on_state is not None:
                await on_state(message)
            choice = next_subtask(message)
            if choice is not None:
                # The trial may have ended (trial_end and the close already received, unread) as we chose.
                with contextlib.suppress(ConnectionClosedOK):
                    await sock.send("select_subtask", subtask=choice)


async def play_every_trial(player: Player, answers: dict[str, int] | None = None) -> list[tuple[dict[str, Any],
                                                                                                dict[str, Any]]]:
    """Play the participant's remaining trials to their end (answering questionnaire ``q`` with ``answers``);
    returns each trial's ``(session["trial"], hello)``."""
    played = []
    while (session := await player.session())["state"] in ("practice", "trial", "questionnaire"):
        if session["state"] == "questionnaire":
            (await player.post("/api/session/questionnaire",
                               {"questionnaire_id": "q", "answers": answers or {"a": 1}})).raise_for_status()
            continue
        sock = await player.socket()
        hello = await sock.recv()
        await play_to_end(sock)
        await sock.close()
        played.append((session["trial"], hello))
    return played


async def play_until(sock: Socket, tick: int) -> dict[str, Any]:
    """Read ``sock`` (choosing the first available subtask whenever none is chosen) until a ``state`` of
    ``tick`` or later; returns that state."""
    while True:
        message = await sock.recv()
        if message["type"] == "state":
            if message["subtask"] is None and message["available"]:
                await sock.send("select_subtask", subtask=message["available"][0])
            if message["tick"] >= tick:
                return message


async def until_unloaded(services: Any, timeout: float = 10.0) -> None:
    """Wait until the server process holds no live game (a disconnected trial is unloaded when its reconnect
    grace window ends); fails after ``timeout`` seconds."""
    deadline = time.monotonic() + timeout
    while services.registry.games and time.monotonic() < deadline:
        await asyncio.sleep(0.05)
    assert not services.registry.games, "the trial must be unloaded after the grace window"


class ManualClock:
    """A wall clock for the rounds' limit and idle nudge (``server.game.clock.Clock``) that moves only when the
    test calls :meth:`advance` (from its own thread: the server's loop is woken thread-safely)."""

    def __init__(self) -> None:
        self.t = 0.0
        self._lock = threading.Lock()
        self._waiters: list[tuple[asyncio.AbstractEventLoop, asyncio.Event]] = []

    def now(self) -> float:
        return self.t

    async def wait(self, event: asyncio.Event, seconds: float | None) -> None:
        deadline = None if seconds is None else self.t + seconds
        while not event.is_set() and (deadline is None or self.t < deadline):
            moved = asyncio.Event()
            with self._lock:
                self._waiters.append((asyncio.get_running_loop(), moved))
            waits = {asyncio.ensure_future(event.wait()), asyncio.ensure_future(moved.wait())}
            _, pending = await asyncio.wait(waits, return_when=asyncio.FIRST_COMPLETED)
            for task in pending:
                task.cancel()

    async def sleep(self, seconds: float) -> None:
        await self.wait(asyncio.Event(), seconds)

    def advance(self, seconds: float) -> None:
        with self._lock:
            self.t += seconds
            waiters, self._waiters = self._waiters, []
        for loop, moved in waiters:
            loop.call_soon_threadsafe(moved.set)
