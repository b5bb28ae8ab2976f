"""Killing the server process (SIGKILL) mid-trial and starting it again on the same database: what was
flushed is intact, nothing is corrupt, and the participant resumes from the last flushed tick (or the
trial is marked per the study's policy)."""

from __future__ import annotations

import asyncio
import time

import pytest
from sqlalchemy import text
from steakhouse_testing import Player, ProcessServer, play_to_end, play_until, wait_stored

from planner.kb import KnowledgeBase
from planner.state import WorldState
from store import trials
from store.engine import Store
from store.tables import TrialRow

pytestmark = pytest.mark.slow


def check_store(db_url: str, trial_id: int) -> tuple[TrialRow, list[int]]:
    """Every stored tick parses back into a world and a KB, and the ticks are 1..n without gaps."""
    store = Store(db_url)
    try:
        with store.transaction() as session:
            if store.dialect == "sqlite":
                assert session.execute(text("PRAGMA integrity_check")).scalar() == "ok"
            row = session.get_one(TrialRow, trial_id)
            rows = trials.ticks(session, trial_id)
            for tick in rows:
                world = WorldState.from_dict(tick.world_state)
                assert world.tick == tick.tick
                KnowledgeBase.from_dict(tick.kb_state)
            return row, [t.tick for t in rows]
    finally:
        store.dispose()


def test_sigkill_mid_trial_then_restart_resumes_from_the_last_flushed_tick(db_url, study_file, tmp_path):
    study = study_file(world={"orders": 2, "horizon": 400, "kb_delay": 1})
    log = tmp_path / "server.log"
    server = ProcessServer(study=study, database_url=db_url, workers=1, log=log).start()
    try:
        async def before_crash():
            player = Player(server.url)
            await player.ready()
            sock = await player.socket()
            hello = await sock.recv()
            seen = await play_until(sock, 30)
            await asyncio.to_thread(wait_stored, db_url, {hello["trial"]["id"]: 30})
            server.kill()
            await sock.close()
            await player.close()
            return player.token, hello, seen

        token, hello, _seen = asyncio.run(before_crash())
        trial_id = hello["trial"]["id"]
        row, flushed = check_store(db_url, trial_id)
        assert row.status == "running"
        assert flushed == list(range(1, len(flushed) + 1)) and len(flushed) >= 25, flushed[-3:]

        server = ProcessServer(study=study, database_url=db_url, workers=0, log=log).start()

        async def after_restart():
            player = Player(server.url)
            player.token = token
            sock = await player.socket()
            hello2 = await sock.recv()
            state = await sock.recv()
            end = await play_to_end(sock)
            await sock.close()
            await player.close()
            return hello2, state, end

        hello2, state, end = asyncio.run(after_restart())
        assert hello2["trial"]["id"] == trial_id and hello2["resumed"] is True
        assert hello2["tick"] == len(flushed) == state["tick"]
        assert end["status"] == "finished"
        row, ticks = check_store(db_url, trial_id)
        assert ticks == list(range(1, end["ticks"] + 1))
        assert (row.status, row.ticks) == ("finished", end["ticks"])
    finally:
        server.kill()


def test_away_longer_than_the_grace_window_after_a_restart_the_trial_is_abandoned(db_url, study_file, tmp_path):
    """A restart starts the grace window again (the outage was not the participant's); a participant who then
    stays away longer than it has their round abandoned, as one who left."""
    study = study_file(reconnect={"grace_seconds": 0.5, "after_grace": "abandon"})
    env = {"STEAKHOUSE_SWEEP_INTERVAL_S": "0.2"}
    server = ProcessServer(study=study, database_url=db_url, workers=0, env=env, log=tmp_path / "s.log").start()
    try:
        async def before_crash():
            player = Player(server.url)
            await player.ready()
            sock = await player.socket()
            hello = await sock.recv()
            await play_until(sock, 10)
            server.kill()
            await sock.close()
            await player.close()
            return player.token, hello

        token, hello = asyncio.run(before_crash())
        server = ProcessServer(study=study, database_url=db_url, workers=0, env=env, log=tmp_path / "s.log").start()
        time.sleep(1.0)  # away for longer than the window after the restart

        async def after_restart():
            player = Player(server.url)
            player.token = token
            session = await player.session()
            sock = await player.socket()
            reply = await sock.recv()
            await sock.close()
            await player.close()
            return session, reply

        session, reply = asyncio.run(after_restart())
        row, ticks = check_store(db_url, hello["trial"]["id"])
        assert (row.status, row.end_reason) == ("abandoned", "grace_expired")
        # The only main round was abandoned: the study's screen-out outcome (docs/operations.md §8).
        assert session["state"] == "screened_out" and session["completion"]["reason"] == "abandoned_rounds"
        assert reply["type"] == "error" and reply["code"] == "no_trial"
        assert ticks == list(range(1, len(ticks) + 1))
    finally:
        server.kill()
