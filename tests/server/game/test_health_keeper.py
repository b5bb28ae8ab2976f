"""The robot health of a live trial (``server.game.health_keeper``): the decision that makes the trial invalid is
reported at once (the server log, one ``trial_invalid`` event, the trial row); at the end the health is judged over
the decisions made and stored; a suspended trial stores its counts."""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Iterator

import pytest
from steakhouse_live_parts import Events, meta
from steakhouse_stored_trial import new_trial

from server.game.health_keeper import HealthKeeper
from store.engine import Store
from store.studies import sync_study
from store.tables import TrialRow
from study_config.catalog import load_one
from study_config.study.validity import Validity

HORIZON = 20


@pytest.fixture
def trial(db_url: str, study_file) -> Iterator[tuple[Store, int]]:
    """A migrated store holding one trial row; the trial's id."""
    store = Store(db_url)
    store.migrate()
    loaded = load_one(study_file())
    with store.transaction() as session:
        sync_study(session, loaded.study)
    _, trial_id = new_trial(store, loaded)
    yield store, trial_id
    store.dispose()


def stored(store: Store, trial_id: int) -> tuple[int | None, int | None, int | None, str | None]:
    with store.transaction() as session:
        row = session.get(TrialRow, trial_id)
        assert row is not None
        return row.decisions, row.missed_decisions, row.failed_decisions, row.invalid_reason


def test_the_decision_that_makes_the_trial_invalid_is_reported_once_and_stored(
        trial: tuple[Store, int], caplog: pytest.LogCaptureFixture) -> None:
    store, trial_id = trial
    events = Events()

    async def scenario() -> tuple[bool, bool]:
        # 10 % of the horizon's 20 decisions may be lost: the third lost one is one too many
        keeper = HealthKeeper.fresh(Validity(max_missed_decisions_pct=10), HORIZON, store, meta(trial_id=trial_id),
                                    events)
        keeper.record(missed=True)
        keeper.record(missed=False, failed=True)
        valid_after_two = not keeper.health.invalid
        keeper.record(missed=True)
        keeper.record(missed=True)
        await keeper.settle()
        return valid_after_two, keeper.health.invalid

    with caplog.at_level(logging.WARNING, logger="server.game.live"):
        valid_after_two, invalid = asyncio.run(scenario())
    assert valid_after_two and invalid
    assert events.kinds() == ["trial_invalid"], "said once, when it happened"
    assert events.kept[0][1]["missed"] == 2 and events.kept[0][1]["failed"] == 1
    assert f"trial {trial_id} (participant p-3) is invalid" in caplog.text
    decisions, missed, failed, reason = stored(store, trial_id)
    assert (decisions, missed, failed) == (4, 3, 1) and reason is not None and "missed" in reason


def test_at_the_end_the_share_is_judged_over_the_decisions_made(trial: tuple[Store, int]) -> None:
    store, trial_id = trial
    events = Events()

    async def scenario() -> bool:
        keeper = HealthKeeper.fresh(Validity(max_missed_decisions_pct=10), HORIZON, store, meta(trial_id=trial_id),
                                    events)
        keeper.record(missed=True)  # 1 of a horizon of 20 is within 10 %; 1 of the 3 made is not
        keeper.record(missed=False)
        keeper.record(missed=False)
        during = keeper.health.invalid
        keeper.finish()
        await keeper.settle()
        return during

    assert asyncio.run(scenario()) is False
    assert events.kinds() == ["trial_invalid"]
    assert stored(store, trial_id)[:3] == (3, 1, 0) and stored(store, trial_id)[3] is not None


def test_a_suspended_trial_keeps_its_counts_and_a_store_it_cannot_reach_does_not_stop_it(
        trial: tuple[Store, int], db_url: str) -> None:
    store, trial_id = trial

    async def scenario(on: Store) -> None:
        keeper = HealthKeeper.fresh(Validity(), HORIZON, on, meta(trial_id=trial_id), Events())
        keeper.record(missed=False)
        keeper.record(missed=False)
        await keeper.keep()

    asyncio.run(scenario(store))
    assert stored(store, trial_id) == (2, 0, 0, None)
    gone = Store(db_url.rsplit("/", 1)[0] + "/no_such_database")
    asyncio.run(scenario(gone))  # no exception: the counts are recounted from the ticks on resume
    gone.dispose()
