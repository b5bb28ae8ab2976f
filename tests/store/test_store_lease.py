"""The lease on a live round (``store/lease.py``): one holder at a time, enforced by the store. A takeover raises
the epoch; ticks, events, ends and health counts of an older epoch are refused, whether they come before or race
the takeover; renewals keep the round's crash-aware clock; the grace window counts time away while a server was
up."""

from __future__ import annotations

import threading
from datetime import timedelta
from typing import Any

from sqlalchemy import select
from steakhouse_stored_trial import new_trial

from store import lease, trials
from store.tables import EventRow, TickRow, TrialRow
from store.types import utcnow
from store.writer import write_batch


def tick(trial_id: int, number: int, epoch: int) -> dict[str, Any]:
    return {"trial_id": trial_id, "tick": number, "recorded_at": utcnow(), "human_action": "stay",
            "robot_action": "stay", "action_source": "idle", "subtask": None, "kb_summary": {}, "world_summary": {},
            "kb_gap": {}, "kb_gap_total": 0, "robot_in_fov": False, "lateness_ms": 0.0, "decision_ms": 1.0,
            "robot_missed": False, "robot_info": None, "world_state": {"tick": number}, "kb_state": {},
            "controller": {}, "epoch": epoch}


def event(participant_id: int, trial_id: int | None, kind: str, epoch: int | None) -> dict[str, Any]:
    return {"participant_id": participant_id, "trial_id": trial_id, "tick": 0, "kind": kind, "payload": {},
            "created_at": utcnow(), "epoch": epoch}


def take(store, trial_id: int, owner: str) -> int:
    with store.transaction() as session:
        row = session.get(TrialRow, trial_id)
        return lease.take(session, row, owner)


def stored_ticks(store, trial_id: int) -> list[tuple[int, int | None]]:
    with store.transaction() as session:
        return [(t.tick, t.epoch) for t in trials.ticks(session, trial_id)]


def beat(trial_id: int, epoch: int, **fields: Any) -> lease.Beat:
    values: dict[str, Any] = {"away_since": None, "connected_s": 1.0, "open_wait_s": None, **fields}
    return lease.Beat(trial_id, epoch, **values)


def test_a_takeover_fences_the_old_holder_out_of_the_store(store, loaded):
    participant_id, trial_id = new_trial(store, loaded)
    first = take(store, trial_id, "host-a:1")
    written = write_batch(store, [tick(trial_id, 1, first), tick(trial_id, 2, first)],
                          [event(participant_id, trial_id, "connect", first)], [beat(trial_id, first)])
    assert written.stale == set() and written.refused == 0
    second = take(store, trial_id, "host-b:2")
    assert second == first + 1
    late = write_batch(store, [tick(trial_id, 3, first)], [event(participant_id, trial_id, "interrupt", first),
                                                          event(participant_id, None, "join_refused", None)],
                       [beat(trial_id, first, connected_s=99.0)])
    assert late.stale == {(trial_id, first)} and late.refused == 2, "the old holder's tick and event are refused"
    assert stored_ticks(store, trial_id) == [(1, first), (2, first)]
    write_batch(store, [tick(trial_id, 3, second)], [], [beat(trial_id, second, connected_s=5.0)])
    assert stored_ticks(store, trial_id) == [(1, first), (2, first), (3, second)]
    with store.transaction() as session:
        row = session.get(TrialRow, trial_id)
        assert (row.lease_owner, row.connected_s) == ("host-b:2", 5.0), "the stale renewal changed nothing"
        kinds = [(e.kind, e.epoch) for e in session.scalars(select(EventRow).order_by(EventRow.id))]
        assert ("interrupt", first) not in kinds and ("join_refused", None) in kinds
        assert not trials.end(session, trial_id, status="finished", reason="delivered", epoch=first)
        trials.record_health(session, trial_id, decisions=9, missed=9, invalid_reason="stale", epoch=first)
    with store.transaction() as session:
        row = session.get(TrialRow, trial_id)
        assert row.status == "running" and row.invalid_reason is None, "a stale end and health are refused"
        assert trials.end(session, trial_id, status="finished", reason="delivered", epoch=second)


def test_a_takeover_racing_the_old_holders_batches_never_interleaves_with_them(store, loaded):
    """The old holder writes a tick per transaction as fast as it can while the new one takes the lease and reads
    the last stored tick in its transaction: every tick of the old epoch is at or before what the new holder read,
    so it resumes from exactly what the store has and no tick of the old holder lands after it."""
    _, trial_id = new_trial(store, loaded)
    first = take(store, trial_id, "host-a:1")
    stop = threading.Event()
    written: list[int] = []

    def old_holder() -> None:
        number = 0
        while not stop.is_set() and number < 2000:
            number += 1
            if write_batch(store, [tick(trial_id, number, first)], []).stale:
                return
            written.append(number)

    thread = threading.Thread(target=old_holder)
    thread.start()
    while len(written) < 5:
        pass
    with store.transaction() as session:
        row = session.get(TrialRow, trial_id)
        second = lease.take(session, row, "host-b:2")
        last = trials.last_tick(session, trial_id)
        read = last.tick if last is not None else 0
    stop.set()
    thread.join()
    old = [number for number, epoch in stored_ticks(store, trial_id) if epoch == first]
    assert second == first + 1 and old == list(range(1, read + 1)), (read, old[-3:])


def test_away_time_counts_while_a_server_is_up_and_restarts_at_a_server_start(store, loaded):
    _, trial_id = new_trial(store, loaded)
    epoch = take(store, trial_id, "host-a:1")
    now = utcnow()
    with store.transaction() as session:
        row = session.get(TrialRow, trial_id)
        assert lease.away_seconds(row, now) == 0.0, "connected to a live holder"
    left = now - timedelta(seconds=20)
    with store.transaction() as session:
        lease.renew(session, [beat(trial_id, epoch, away_since=left)], now)
    with store.transaction() as session:
        row = session.get(TrialRow, trial_id)
        assert 19.5 < lease.away_seconds(row, now) < 20.5, "away from a live holder since the disconnect"
        # The holder dies (its lease runs out) with the participant connected: away from its last renewal.
        lease.renew(session, [beat(trial_id, epoch)], now - timedelta(seconds=30))
    later = now + timedelta(seconds=lease.LEASE_TTL_S)
    with store.transaction() as session:
        row = session.get(TrialRow, trial_id)
        assert not lease.holder_alive(row, later)
        assert 34 < lease.away_seconds(row, later) < 36
        assert lease.restart_count(session, [loaded.id], later) == 1
    with store.transaction() as session:
        row = session.get(TrialRow, trial_id)
        assert lease.away_seconds(row, later) == 0.0, "a server start restarts the count"


def test_a_wait_cut_short_by_a_crash_is_stored_once_under_its_holders_epoch(store, loaded):
    participant_id, trial_id = new_trial(store, loaded)
    epoch = take(store, trial_id, "host-a:1")
    write_batch(store, [], [], [beat(trial_id, epoch, open_wait_s=7.25, connected_s=31.0)])
    with store.transaction() as session:
        row = session.get(TrialRow, trial_id)
        assert lease.recover_wait(session, row, 4) == 7.25
    with store.transaction() as session:
        row = session.get(TrialRow, trial_id)
        assert lease.recover_wait(session, row, 4) is None, "recovered once"
        waits = list(session.scalars(select(EventRow).where(EventRow.kind == "wait")))
        assert [(w.payload["seconds"], w.epoch, w.participant_id) for w in waits] == [(7.25, epoch, participant_id)]
        assert row.connected_s == 31.0


def test_a_released_lease_keeps_its_epoch_for_the_last_rows(store, loaded):
    _, trial_id = new_trial(store, loaded)
    epoch = take(store, trial_id, "host-a:1")
    with store.transaction() as session:
        lease.release(session, [beat(trial_id, epoch, connected_s=12.0, open_wait_s=2.0)])
    assert write_batch(store, [tick(trial_id, 1, epoch)], []).stale == set(), "a shutdown's last flush is stored"
    with store.transaction() as session:
        row = session.get(TrialRow, trial_id)
        assert row.lease_owner is None and row.away_since is not None and row.open_wait_s == 2.0
        assert not lease.holder_alive(row, utcnow())
        assert session.scalar(select(TickRow.epoch).where(TickRow.trial_id == trial_id)) == epoch
