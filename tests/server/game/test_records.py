"""What a live trial stores (``server.game.records``): each event and each step lands in the store with the tick it
happened at and the round's lease epoch, and is counted toward the round's taking part; the end is refused when
another process runs the round now."""

from __future__ import annotations

import asyncio
from collections.abc import Iterator

import pytest
from sqlalchemy import select
from steakhouse_live_parts import engine, meta
from steakhouse_stored_trial import new_trial

from planner.geometry import Action
from server.game.records import TrialRecords
from server.game.taking_part import TakingPart
from server.protocol.server import Error
from server.robots import RobotChoice
from store import trials
from store.engine import Store
from store.studies import sync_study
from store.tables import EventRow, TrialRow
from store.writer import BatchWriter
from study_config.catalog import LoadedStudy, load_one
from study_config.study.validity import Validity


@pytest.fixture
def stored(db_url: str, study_file) -> Iterator[tuple[Store, LoadedStudy, int, int]]:
    store = Store(db_url)
    store.migrate()
    loaded = load_one(study_file())
    with store.transaction() as session:
        sync_study(session, loaded.study)
    yield store, loaded, *new_trial(store, loaded)
    store.dispose()


def test_events_and_steps_are_stored_at_their_tick_and_counted(stored) -> None:
    store, _, participant_id, trial_id = stored
    part = TakingPart(Validity(), 5.0, judged=True)
    cook = engine()

    async def scenario() -> None:
        records = TrialRecords(BatchWriter(store), meta(trial_id=trial_id, participant_id=participant_id), cook, part)
        records.event("select_subtask", {"seq": 1, "subtask": "pickup_onion", "available": True})
        outcome = cook.advance(Action.STAY)
        records.tick(outcome, RobotChoice(Action.STAY, decision_ms=2.5), 1.25, 0.5)
        records.event("nudge", {"repeat": 1})
        await records.writer.flush()

    asyncio.run(scenario())
    with store.transaction() as session:
        events = [(e.kind, e.tick, e.epoch) for e in session.scalars(
            select(EventRow).where(EventRow.trial_id == trial_id).order_by(EventRow.id))]
        ticks = [(t.tick, t.lateness_ms, t.decision_ms, t.round_seconds) for t in trials.ticks(session, trial_id)]
    assert events == [("select_subtask", 0, 0), ("nudge", 1, 0)]
    assert ticks == [(1, 1.25, 2.5, 0.5)]
    assert (part.activity().selections, part.activity().ticks) == (1, 1)


def test_the_end_is_not_stored_when_another_process_runs_the_round(stored) -> None:
    store, loaded, participant_id, trial_id = stored
    records = TrialRecords(BatchWriter(store), meta(trial_id=trial_id, participant_id=participant_id, epoch=5),
                           engine(), TakingPart(Validity(), 5.0, judged=True))
    code, message = asyncio.run(records.store_end(store, loaded.study, "finished", "delivered"))
    assert code == 4000 and isinstance(message, Error) and message.code == "replaced"
    with store.transaction() as session:
        row = session.get(TrialRow, trial_id)
        assert row is not None and row.status == "running"
