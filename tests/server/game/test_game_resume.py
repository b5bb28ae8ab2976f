"""A reconnection that read the participant's step just before their trial ended does not start the trial
again: ``prepare_trial`` checks the step against the participant's progress in its own transaction."""

from __future__ import annotations

import pytest
from steakhouse_testing import write_study

from server.flow import service
from server.flow.progress import Move, Phase
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
