"""A trial whose robot misses its deadlines is marked invalid as it happens: event, trial row, log, admin."""

from __future__ import annotations

import asyncio
import logging

import httpx
import pytest
from steakhouse_testing import Player, play_to_end

from store import trials
from store.tables import EventRow, TrialRow
from study_config.study.validity import DEFAULT_MAX_MISSED_DECISIONS_PCT

pytestmark = pytest.mark.store_agnostic

ADMIN = {"Authorization": "Bearer admin-secret"}


def test_a_trial_with_a_frozen_robot_is_flagged_invalid_with_its_reason(live_server, study_file, monkeypatch,
                                                                       caplog):
    from steakhouse_test_robots import slow

    monkeypatch.setenv("STEAKHOUSE_TEST_SLOW_S", "0.1")
    study = study_file(world={"orders": 1, "horizon": 20, "kb_delay": 1}, validity={"max_missed_decisions_pct": 10})
    server = live_server([study], robot_factory=slow)

    async def scenario():
        player = Player(server.url)
        await player.ready()
        sock = await player.socket()
        hello = await sock.recv()
        end = await play_to_end(sock)
        await sock.close()
        await player.close()
        return hello, end

    with caplog.at_level(logging.WARNING, logger="server.game.live"):
        hello, end = asyncio.run(scenario())
    trial_id = hello["trial"]["id"]
    assert end["ticks"] == 20
    with server.services.store.transaction() as session:
        row = session.get(TrialRow, trial_id)
        stored = (row.decisions, row.missed_decisions, row.invalid_reason)
        events = [e.payload for e in session.query(EventRow).filter_by(trial_id=trial_id, kind="trial_invalid")]
    # The first decision has FIRST_DECISION_S (the clock starts once it is in); every later one is too late.
    assert stored == (20, 19, "robot decisions missed their deadline: 19 of 20 (95.0 % > 10 %)")
    # Marked the moment 3 of at most 20 decisions had missed (more than 10 % of the horizon).
    assert len(events) == 1 and events[0]["missed"] == 3 and events[0]["decisions"] == 4
    assert any("is invalid" in r.getMessage() and str(trial_id) in r.getMessage() for r in caplog.records)
    listed = httpx.get(f"{server.url}/api/admin/trials", headers=ADMIN, params={"study_id": "tiny"}).json()
    mine = next(t for t in listed if t["trial_id"] == trial_id)
    assert mine["invalid"] and mine["invalid_reason"] == stored[2] and mine["missed_decisions_pct"] == 95.0
    people = httpx.get(f"{server.url}/api/admin/participants", headers=ADMIN, params={"study_id": "tiny"}).json()
    assert [p["invalid_trials"] for p in people] == [1]


def test_the_trial_row_counts_every_decision_and_every_miss_the_ticks_recorded(live_server, study_file):
    """Whatever the machine's speed: one decision per tick, the misses are the ticks where the robot missed,
    and the trial is invalid exactly when they pass the study's share (the default, 5 %)."""
    # the test studies allow every decision to miss (steakhouse_testing.write_study); this one has the default
    server = live_server([study_file(world={"orders": 1, "horizon": 20, "kb_delay": 1},
                                     validity={"max_missed_decisions_pct": DEFAULT_MAX_MISSED_DECISIONS_PCT})])

    async def scenario():
        player = Player(server.url)
        await player.ready()
        sock = await player.socket()
        hello = await sock.recv()
        end = await play_to_end(sock)
        await sock.close()
        await player.close()
        return hello, end

    hello, end = asyncio.run(scenario())
    trial_id = hello["trial"]["id"]
    with server.services.store.transaction() as session:
        row = session.get(TrialRow, trial_id)
        missed = sum(1 for t in trials.ticks(session, trial_id) if t.robot_missed)
        assert (row.decisions, row.missed_decisions) == (end["ticks"], missed)
        assert (row.invalid_reason is not None) == (100 * missed > DEFAULT_MAX_MISSED_DECISIONS_PCT * end["ticks"])
