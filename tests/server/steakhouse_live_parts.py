"""Pieces for the unit tests of a live game's parts (``server.game.pacing``, ``link``, ``choices``, ``decisions``,
``hints``, ``health_keeper``): a socket that keeps what it was sent, a clock moved by hand on the test's own event
loop, an event log that keeps what it is given, a trial's facts, and an engine in the practice kitchen."""

from __future__ import annotations

import asyncio
import json
from dataclasses import replace
from typing import Any

from planner.geometry import Direction
from planner.kb import initial_kb, update_kb
from planner.rules import Rules
from planner.state import AgentState, WorldState, initial_state
from server.game import snapshot
from server.game.connection import Connection
from server.game.engine import TrialEngine
from server.game.link import ParticipantLink
from server.game.meta import TrialMeta
from study_config import load_layout

PRACTICE = load_layout("practice")  # board (5,1), sink (7,1), serving hatch (1,3), grill (8,4), meat crate (8,5)
RULES = Rules(orders=1, horizon=400)


class Socket:
    """What a websocket was sent (JSON decoded) and the code it was closed with."""

    def __init__(self) -> None:
        self.sent: list[dict[str, Any]] = []
        self.closed_with: int | None = None

    async def send_text(self, text: str) -> None:
        self.sent.append(json.loads(text))

    async def close(self, code: int = 1000) -> None:
        self.closed_with = code

    def types(self) -> list[str]:
        return [m["type"] for m in self.sent]


def connection() -> tuple[Connection, Socket]:
    socket = Socket()
    return Connection(socket), socket


async def closed(conn: Connection, socket: Socket) -> Socket:
    """Close ``conn`` (if nobody did) and wait until every message it queued was sent: the socket, complete."""
    conn.begin_close(1000)
    await asyncio.wait_for(conn.wait_closed(), 5)
    return socket


class HandClock:
    """A :class:`server.game.clock.Clock` that moves only by :meth:`advance`, on the test's event loop."""

    def __init__(self) -> None:
        self.t = 0.0
        self._moved = asyncio.Event()
        self.waiting = asyncio.Event()
        """Set while something waits on this clock."""

    def now(self) -> float:
        return self.t

    async def wait(self, event: asyncio.Event, seconds: float | None) -> None:
        deadline = None if seconds is None else self.t + seconds
        self.waiting.set()
        try:
            while not event.is_set() and (deadline is None or self.t < deadline):
                self._moved.clear()
                waits = {asyncio.ensure_future(event.wait()), asyncio.ensure_future(self._moved.wait())}
                _, pending = await asyncio.wait(waits, return_when=asyncio.FIRST_COMPLETED)
                for task in pending:
                    task.cancel()
        finally:
            self.waiting.clear()

    async def sleep(self, seconds: float) -> None:
        await self.wait(asyncio.Event(), seconds)

    def advance(self, seconds: float) -> None:
        self.t += seconds
        self._moved.set()


async def waits_on(clock: HandClock, task: asyncio.Future[Any]) -> None:
    """Return once ``task`` waits on ``clock`` (it must not have finished meanwhile)."""
    waiting = asyncio.ensure_future(clock.waiting.wait())
    await asyncio.wait({waiting, task}, return_when=asyncio.FIRST_COMPLETED)
    waiting.cancel()
    assert not task.done(), "the part did not wait on its clock"


class Events:
    """An event log (``server.game.records.EventLog``) that keeps the events it is given."""

    def __init__(self) -> None:
        self.kept: list[tuple[str, dict[str, Any]]] = []

    def __call__(self, kind: str, payload: dict[str, Any]) -> None:
        self.kept.append((kind, payload))

    def kinds(self) -> list[str]:
        return [kind for kind, _ in self.kept]


def meta(**changes: Any) -> TrialMeta:
    base = TrialMeta(trial_id=7, attempt=1, participant_id=3, participant="p-3", study_id="tiny", kind="main",
                     index=0, number=1, total=1, kind_total=1, condition="c", robot="stay", kitchen="practice",
                     view="top_down", seed=11, test_run=False)
    return replace(base, **changes)


def world_with(*, pos: tuple[int, int] = (4, 2), facing: Direction = Direction.SOUTH, held: str | None = None,
               board: int | None = None) -> WorldState:
    world = initial_state(PRACTICE, RULES)
    return replace(world, human=AgentState(pos, facing, held), boards=(board,))


def engine(world: WorldState | None = None, rules: Rules = RULES) -> TrialEngine:
    world = world or initial_state(PRACTICE, rules)
    kb = update_kb(initial_kb(world), PRACTICE, world, angle=360.0, kb_delay=0)
    return TrialEngine(PRACTICE, rules, angle=120.0, kb_delay=1, seed=3, world=world, kb=kb, blocked_ticks=5)


def opened(link: ParticipantLink, conn: Connection) -> None:
    """Open ``conn`` on ``link`` as the game does (hello and state of a trial in the practice kitchen)."""
    game = engine()
    hello = snapshot.hello(meta(), game, mode="fixed_rate", rate=5.0, resumed=False, limit=10_000)
    link.open(conn, hello, snapshot.state(game, mode="fixed_rate", rate=5.0, ack=0), game.tick)
