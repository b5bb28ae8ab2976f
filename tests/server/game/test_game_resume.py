"""A reconnection racing the end of its trial does not start the trial again: ``prepare_trial`` checks the step
against the participant's progress in its own transaction, and a reconnection arriving while the trial's end is
being stored waits for it; a round resumed from the store keeps the wall-clock time it has already run."""

from __future__ import annotations

import asyncio
import threading
from typing import Any

import pytest
from steakhouse_testing import ManualClock, Player, ThreadServer, eventually, play_until, write_study

from server.app import create_app
from server.flow import service
from server.flow.progress import Move, Phase
from server.game import registry
from server.game.resume import StepPassed, prepare_trial
from store import trials
from store.engine import Store
from store.studies import sync_study
from store.tables import ParticipantRow, TrialRow
from study_config.catalog import load_one


def test_a_step_read_before_its_trial_ended_gets_no_second_attempt(db_url, tmp_path) -> None:
    loaded = load_one(write_study(tmp_path))
    store = Store(db_url)
    try:
        store.migrate()
        with store.transaction() as session:
            sync_study(session, loaded.study)
        pid = service.join(store, loaded, {}, False).participant.id
        service.move(store, pid, Move.ACCEPT_CONSENT)
        service.move(store, pid, Move.FINISH_INSTRUCTIONS)
        with store.transaction() as session:
            row = session.get(ParticipantRow, pid)
            assert row is not None
            step = service.progress_of(row).current  # what a reconnecting socket read
        first = prepare_trial(store, loaded, pid, step)
        assert first.outcome == "new"
        assert prepare_trial(store, loaded, pid, step).outcome == "resume"
        service.end_trial(store, pid, first.trial.id, "main", 0, status=trials.FINISHED, reason="delivered",
                          ticks=40, delivered=1, score=20, study=loaded.study)
        with pytest.raises(StepPassed) as passed:
            prepare_trial(store, loaded, pid, step)  # the same step, read before the trial ended
        assert passed.value.progress.phase not in (Phase.PRACTICE, Phase.TRIAL)
        with store.transaction() as session:
            assert [t.id for t in session.query(TrialRow).filter_by(participant_id=pid)] == [first.trial.id]
    finally:
        store.dispose()


def test_a_reconnection_while_the_trial_is_being_stored_as_ended_does_not_resume_it(live_server, study_file,
                                                                                       monkeypatch) -> None:
    """The trial reaches its horizon and its end is being stored when the participant's browser reconnects: the
    reconnection waits for the end to be stored and gets ``no_trial``, instead of resuming the trial from a store
    still missing its last ticks (which replayed them: a tick stored twice, a reconnection back in time). The end
    is held for up to a second for a reconnection that did not wait to show itself."""
    server = live_server([study_file(world={"orders": 1, "horizon": 8, "kb_delay": 1})])
    order: list[str] = []
    ending, second_prepare = threading.Event(), threading.Event()
    original_end, original_prepare = service.end_trial, prepare_trial

    def slow_end(*args, **kwargs):
        ending.set()
        second_prepare.wait(timeout=1.0)
        result = original_end(*args, **kwargs)
        order.append("end stored")
        return result

    def watched_prepare(*args, **kwargs):
        order.append("prepare")
        if order.count("prepare") == 2:
            second_prepare.set()
        return original_prepare(*args, **kwargs)

    monkeypatch.setattr(service, "end_trial", slow_end)
    monkeypatch.setattr(registry, "prepare_trial", watched_prepare)

    async def scenario() -> dict[str, Any]:
        player = Player(server.url)
        try:
            await player.ready(PROLIFIC_PID="late")
            first = await player.socket()
            assert (await first.recv())["type"] == "hello"
            assert await asyncio.to_thread(ending.wait, 60)
            again = await player.socket()
            reply: dict[str, Any] = await again.recv()
            await again.close()
            await first.close()
            return reply
        finally:
            await player.close()

    reply = asyncio.run(scenario())
    assert reply["type"] == "error" and reply["code"] == "no_trial"
    assert order == ["prepare", "end stored", "prepare"]


def test_a_round_resumed_by_a_restarted_server_keeps_its_time_limit(live_server, make_settings, study_file) -> None:
    """The waiting clock's wall-clock limit counts the seconds already played: after 12 of its 20 s on one server,
    the round resumed on a restarted one ends at the limit 9 s later (and its ticks go on counting from 12 s), not
    after another 20."""
    study = study_file(timing={"mode": "wait_for_participant", "tick_rate_hz": 30, "max_round_seconds": 20,
                               "idle_nudge_seconds": 1000}, world={"orders": 4, "horizon": 400})
    before, after = ManualClock(), ManualClock()

    def stored_seconds(server: ThreadServer, trial_id: int) -> float:
        with server.services.store.transaction() as session:
            # 0 while the writer has flushed no tick yet (a busy machine): the caller waits for more.
            return max(((t.round_seconds or 0.0) for t in trials.ticks(session, trial_id)), default=0.0)

    with ThreadServer(create_app(make_settings([study]), clock=before)) as first:
        async def play_a_while() -> tuple[str, int]:
            player = Player(first.url)
            await player.ready()
            sock = await player.socket()
            hello = await sock.recv()
            await play_until(sock, 3)
            before.advance(12.0)
            await play_until(sock, 6)
            await sock.close()
            await player.close()
            return player.token, hello["trial"]["id"]

        token, trial_id = asyncio.run(play_a_while())
        eventually(lambda: stored_seconds(first, trial_id), lambda s: s >= 12.0)
    second = live_server([study], clock=after)

    async def resume() -> tuple[dict[str, Any], dict[str, Any]]:
        player = Player(second.url)
        player.token = token  # the same participant's browser, on the restarted server
        sock = await player.socket()
        hello = await sock.recv()
        after.advance(9.0)
        end = await sock.until(lambda m: m["type"] == "trial_end")
        await sock.close()
        await player.close()
        return hello, end

    hello, end = asyncio.run(resume())
    assert hello["resumed"] is True and hello["trial"]["id"] == trial_id
    assert end["reason"] == "time_limit"
    assert stored_seconds(second, trial_id) >= 12.0
