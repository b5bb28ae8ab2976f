"""Crash and reconnect drills (a killed server or a dropped connection loses nothing beyond the last batch):

- SIGKILL the server while four participants play at once, check the store (every flushed tick intact:
  ticks 1..n of each trial, no duplicates, each parses back), start it again on the same database: every
  participant resumes per the study's policy — within the grace window the same trial at its last stored
  tick, which then plays to the end with its stored ticks unchanged; away longer than the window after the
  restart (which starts it again), with ``restart`` a new attempt at tick 0, the old one kept as it was.
- Drop and restore connections at random (abrupt TCP drops and clean closes) during several trials at
  once: every trial ends with ticks 1..n stored once each, and each reconnection continues where it stood.
"""

from __future__ import annotations

import asyncio
import contextlib
import random
import time
from typing import Any

import pytest
from sqlalchemy import func, select, text
from steakhouse_testing import Player, ProcessServer, play_to_end, play_until, wait_stored
from websockets.exceptions import ConnectionClosed

from planner.kb import KnowledgeBase
from planner.state import WorldState
from store import trials
from store.engine import Store
from store.tables import EventRow, TickRow, TrialRow

pytestmark = pytest.mark.slow
PLAYERS = 4


def stored(db_url: str) -> dict[int, dict[str, Any]]:
    """Per trial: its row's status, attempt and reason, and its ticks (number → world state), after checking
    the database's integrity, that no (trial, tick) is stored twice and that every tick parses back."""
    store = Store(db_url)
    try:
        with store.transaction() as session:
            if store.dialect == "sqlite":
                assert session.execute(text("PRAGMA integrity_check")).scalar() == "ok"
            doubled = session.execute(select(TickRow.trial_id, TickRow.tick).group_by(TickRow.trial_id, TickRow.tick)
                                      .having(func.count() > 1)).all()
            assert not doubled, doubled
            out = {}
            for row in session.scalars(select(TrialRow)):
                ticks = {}
                for tick in trials.ticks(session, row.id):
                    world = WorldState.from_dict(tick.world_state)
                    assert world.tick == tick.tick
                    KnowledgeBase.from_dict(tick.kb_state)
                    ticks[tick.tick] = tick.world_state
                out[row.id] = {"status": row.status, "attempt": row.attempt, "reason": row.end_reason,
                               "participant": row.participant_id, "ticks": ticks}
            return out
    finally:
        store.dispose()


async def start_and_play(url: str, pid: str, until: int) -> tuple[Player, Any, int]:
    player = Player(url)
    await player.ready(PROLIFIC_PID=pid)
    sock = await player.socket()
    hello = await sock.recv()
    await play_until(sock, until)
    return player, sock, hello["trial"]["id"]


async def resume(url: str, token: str) -> tuple[dict[str, Any], dict[str, Any], dict[str, Any] | None]:
    player = Player(url)
    player.token = token
    sock = await player.socket()
    hello = await sock.recv()
    first, end = {}, None
    if hello["type"] == "hello":
        first = await sock.recv()
        end = await play_to_end(sock)
    await sock.close()
    await player.close()
    return hello, first, end


async def resume_all(url: str, started: list[tuple[str, int]]) -> list[Any]:
    """Every crashed participant comes back at once (``resume`` for each token)."""
    return list(await asyncio.gather(*(resume(url, token) for token, _ in started)))


def crash(server: ProcessServer, url: str, until: int) -> list[tuple[str, int]]:
    """Four participants play at once until each has reached ``until``; the server is then killed."""
    async def scenario() -> list[tuple[str, int]]:
        started = await asyncio.gather(*(start_and_play(url, f"p{i}", until + 3 * i) for i in range(PLAYERS)))
        reached = {trial_id: until + 3 * i for i, (_, _, trial_id) in enumerate(started)}
        await asyncio.to_thread(wait_stored, server.database_url, reached)
        server.kill()
        for player, sock, _ in started:
            sock.ws.transport.abort()  # the server is gone: no closing handshake to wait for
            await player.close()
        return [(player.token, trial_id) for player, _, trial_id in started]

    return asyncio.run(scenario())


def test_sigkill_during_concurrent_trials_then_restart_every_participant_resumes(db_url, study_file, tmp_path):
    study = study_file(world={"orders": 1, "horizon": 90, "kb_delay": 1})
    log = tmp_path / "server.log"
    server = ProcessServer(study=study, database_url=db_url, workers=1, log=log).start()
    try:
        started = crash(server, server.url, 15)
        before = stored(db_url)
        for _, trial_id in started:
            ticks = sorted(before[trial_id]["ticks"])
            assert before[trial_id]["status"] == "running"
            assert ticks == list(range(1, len(ticks) + 1)) and len(ticks) >= 10, ticks[-3:]
        server = ProcessServer(study=study, database_url=db_url, workers=1, log=log).start()
        resumed = asyncio.run(resume_all(server.url, started))
    finally:
        server.kill()
    after = stored(db_url)
    for (_, trial_id), (hello, first, end) in zip(started, resumed, strict=True):
        flushed = before[trial_id]["ticks"]
        assert hello["trial"]["id"] == trial_id and hello["resumed"] is True
        assert hello["tick"] == len(flushed) == first["tick"], "resume from the last stored tick"
        assert end is not None and end["status"] == "finished"
        final = after[trial_id]
        assert sorted(final["ticks"]) == list(range(1, end["ticks"] + 1))
        assert all(final["ticks"][t] == world for t, world in flushed.items()), "flushed ticks stay as they were"
        assert final["status"] == "finished"


def test_sigkill_longer_than_the_grace_window_restarts_per_policy(db_url, study_file, tmp_path):
    study = study_file(world={"orders": 1, "horizon": 90, "kb_delay": 1},
                       reconnect={"grace_seconds": 0.5, "after_grace": "restart"})
    log = tmp_path / "server.log"
    server = ProcessServer(study=study, database_url=db_url, workers=0, log=log).start()
    try:
        started = crash(server, server.url, 10)
        before = stored(db_url)
        server = ProcessServer(study=study, database_url=db_url, workers=0, log=log).start()
        # The restart starts the grace window again (the outage was not the participants'): they stay away
        # longer than it after the restart.
        time.sleep(1.0)
        resumed = asyncio.run(resume_all(server.url, started))
    finally:
        server.kill()
    after = stored(db_url)
    for (_, trial_id), (hello, first, end) in zip(started, resumed, strict=True):
        old = after[trial_id]
        assert (old["status"], old["reason"]) == ("abandoned", "restarted")
        assert old["ticks"] == before[trial_id]["ticks"], "the abandoned attempt keeps what was flushed"
        assert hello["trial"]["id"] != trial_id and hello["tick"] == 0 and first["tick"] == 0
        new = after[hello["trial"]["id"]]
        assert new["attempt"] == 2 and new["participant"] == old["participant"] and new["status"] == "finished"
        assert end is not None and sorted(new["ticks"]) == list(range(1, end["ticks"] + 1))


async def flaky_participant(url: str, pid: str, rng: random.Random) -> dict[str, Any]:
    """Plays a whole trial while its connection drops at random: abruptly (the TCP connection is cut, no
    close frame) or cleanly, then comes back after a random pause."""
    player = Player(url)
    await player.ready(PROLIFIC_PID=pid)
    connections: list[dict[str, Any]] = []
    end = None
    while end is None:
        sock = await player.socket()
        hello = await sock.recv()
        if hello["type"] == "error" and hello["code"] == "no_trial":
            # The trial ended just as the last connection was being dropped (its trial_end was still on the
            # way, more often on a loaded machine): the store says how it ended.
            end = {"type": "trial_end", "ended_while_dropping": True}
            await sock.close()
            break
        seen: list[int] = []
        drop_at = time.monotonic() + rng.uniform(0.1, 0.6)
        while end is None and time.monotonic() < drop_at:
            try:
                message = await sock.recv(timeout=max(drop_at - time.monotonic(), 0.01))
            except TimeoutError:
                break
            if message["type"] == "trial_end":
                end = message
            elif message["type"] == "state":
                seen.append(message["tick"])
                if message["subtask"] is None and message["available"] and message["hud"]["ticks_left"]:
                    # The trial may end (and the server close the socket) before this arrives: the
                    # trial_end is still read from the socket's buffer next.
                    with contextlib.suppress(ConnectionClosed):
                        await sock.send("select_subtask", subtask=rng.choice(message["available"]))
        connections.append({"hello": hello, "ticks": seen})
        if end is None:
            if rng.random() < 0.5:
                sock.ws.transport.abort()
            else:
                await sock.close()
            await asyncio.sleep(rng.uniform(0.0, 0.3))
        else:
            await sock.close()
    await player.close()
    return {"end": end, "connections": connections}


def test_random_connection_drops_lose_and_double_no_tick(live_server, study_file):
    server = live_server([study_file(world={"orders": 1, "horizon": 120, "kb_delay": 1})])
    rng = random.Random(8)

    async def scenario() -> list[dict[str, Any]]:
        return list(await asyncio.gather(*(flaky_participant(server.url, f"d{i}", random.Random(rng.random()))
                                           for i in range(PLAYERS))))

    results = asyncio.run(scenario())
    wait_stored(server.services.store, {r["connections"][0]["hello"]["trial"]["id"]: r["end"]["ticks"]
                                        for r in results if "ticks" in r["end"]})
    with server.services.store.transaction() as session:
        for result in results:
            end, connections = result["end"], result["connections"]
            trial_id = connections[0]["hello"]["trial"]["id"]
            assert len(connections) >= 2, "the trial must have been interrupted to test anything"
            assert {c["hello"]["trial"]["id"] for c in connections} == {trial_id}
            if end.get("ended_while_dropping"):
                row = session.get(TrialRow, trial_id)
                end = {"status": row.status, "ticks": row.ticks}
            assert end["status"] == "finished"
            ticks = [t.tick for t in trials.ticks(session, trial_id)]
            assert ticks == list(range(1, end["ticks"] + 1)), "every tick stored exactly once"
            last = 0
            for connection in connections:
                hello, seen = connection["hello"], connection["ticks"]
                assert hello["resumed"] is (hello["tick"] > 0)
                assert hello["tick"] >= last, "a reconnection never goes back in time"
                assert seen == list(range(hello["tick"], hello["tick"] + len(seen))), "no gap, no repeat"
                last = seen[-1] if seen else hello["tick"]
            connects = session.scalar(select(func.count()).select_from(EventRow).where(
                EventRow.trial_id == trial_id, EventRow.kind == "connect"))
            assert connects == len(connections)
