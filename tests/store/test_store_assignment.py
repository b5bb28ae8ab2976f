"""Condition-order assignment: least-filled order, the right participants counted, atomic joins."""

from __future__ import annotations

from collections import Counter
from datetime import timedelta

import pytest
from sqlalchemy import update

from server.errors import ApiError
from server.flow import service
from store import assignment, participants
from store.tables import EventRow, ParticipantRow
from store.types import utcnow


def counts(store, loaded) -> list[int]:
    with store.transaction() as session:
        return assignment.order_counts(session, loaded.id, len(loaded.orders), utcnow(),
                                       loaded.study.assignment.in_progress_window_minutes)


def test_least_filled_prefers_the_lowest_index_among_equals():
    assert assignment.least_filled([2, 1, 1]) == 1
    assert assignment.least_filled([0, 0]) == 0
    assert assignment.least_filled([3, 2, 5, 2]) == 1


def test_joins_alternate_between_the_orders(store, loaded):
    indexes = [service.join(store, loaded, {}, False).assignment.order_index for _ in range(6)]
    assert indexes == [0, 1, 0, 1, 0, 1]
    assert counts(store, loaded) == [3, 3]


def test_counted_participants_exclude_test_runs_excluded_screened_out_and_stale(store, loaded):
    joined = [service.join(store, loaded, {}, False) for _ in range(6)]
    ids = [j.participant.id for j in joined]
    old = utcnow() - timedelta(minutes=loaded.study.assignment.in_progress_window_minutes + 1)
    with store.transaction() as session:
        participants.set_flags(session, ids[0], test_run=True, excluded=None, reason=None)
        participants.set_flags(session, ids[1], test_run=None, excluded=True, reason="did not play")
        session.execute(update(ParticipantRow).where(ParticipantRow.id == ids[2]).values(status="screened_out"))
        session.execute(update(ParticipantRow).where(ParticipantRow.id == ids[3]).values(created_at=old))
        session.execute(update(ParticipantRow).where(ParticipantRow.id == ids[5])
                        .values(created_at=old, status="completed"))
    # order 0 had ids 0, 2, 4; order 1 had ids 1, 3, 5: only 4 (in progress, recent) and 5 (completed) count
    assert counts(store, loaded) == [1, 1]
    assert service.join(store, loaded, {}, True).participant.test_run is True
    assert counts(store, loaded) == [1, 1], "a test run is never counted"


def test_a_recruiting_id_joins_once_and_only_its_token_comes_back(store, loaded):
    first = service.join(store, loaded, {"PROLIFIC_PID": "abc", "SESSION_ID": "s1", "OTHER": "dropped"}, False)
    again = service.join(store, loaded, {"PROLIFIC_PID": "abc", "SESSION_ID": "s2"}, False, first.token)
    assert again.rejoined and again.participant.id == first.participant.id and again.token == first.token
    assert again.assignment.order_index == first.assignment.order_index
    assert first.participant.recruiting == {"PROLIFIC_PID": "abc", "SESSION_ID": "s1"}
    other = service.join(store, loaded, {"PROLIFIC_PID": "other"}, False)
    for token in (None, "forged", other.token):
        with pytest.raises(ApiError) as refused:
            service.join(store, loaded, {"PROLIFIC_PID": "abc"}, False, token)
        assert (refused.value.status, refused.value.code) == (409, "already_started")
    with store.transaction() as session:
        found = participants.by_token(session, first.token)
        assert found is not None and found.id == first.participant.id
        refusals = session.query(EventRow).filter(EventRow.kind == "join_refused").all()
        assert [e.participant_id for e in refusals] == [first.participant.id] * 3
    assert counts(store, loaded) == [1, 1]


def test_concurrent_joins_in_threads_stay_balanced(store, loaded, join_at_once):
    tally = Counter(join_at_once(loaded, 41))
    assert sorted(tally.values()) == [20, 21]
    assert counts(store, loaded) == [tally[0], tally[1]]
