"""The background writer commits ticks and events in batches, never twice, and keeps rows it cannot write."""

from __future__ import annotations

import asyncio
import contextlib
from datetime import timedelta
from typing import Any

from steakhouse_stored_trial import new_trial

from store import trials
from store.tables import EventRow, TrialRow
from store.types import utcnow
from store.writer import BatchWriter


def tick_row(trial_id: int, tick: int) -> dict[str, Any]:
    return {"trial_id": trial_id, "tick": tick, "recorded_at": utcnow(), "human_action": "stay",
            "robot_action": "stay", "action_source": "idle", "subtask": None, "kb_summary": {}, "world_summary": {},
            "kb_gap": {"grill": 0}, "kb_gap_total": 0, "robot_in_fov": False, "lateness_ms": 0.5,
            "decision_ms": 1.0, "robot_missed": False, "robot_info": None, "world_state": {"tick": tick},
            "kb_state": {}, "controller": {}}


def stored(store, trial_id: int) -> list[int]:
    with store.transaction() as session:
        return [t.tick for t in trials.ticks(session, trial_id)]


async def committed(store, trial_id: int, count: int, give_up_after: float = 60.0) -> list[int]:
    """The stored ticks once `count` of them are there, polled without flushing (waits on state, not the clock;
    the cap only stops a broken writer from hanging the suite)."""
    loop = asyncio.get_running_loop()
    deadline = loop.time() + give_up_after
    while True:
        seen = await asyncio.to_thread(stored, store, trial_id)
        if len(seen) >= count or loop.time() > deadline:
            return seen
        await asyncio.sleep(0.02)


def test_rows_are_committed_within_the_interval_without_an_explicit_flush(store, loaded):
    participant_id, trial_id = new_trial(store, loaded)

    async def run() -> tuple[list[int], list[int]]:
        writer = BatchWriter(store, interval=0.05)
        writer.start()
        for tick in range(1, 11):
            writer.add_tick(tick_row(trial_id, tick))
        writer.add_event({"participant_id": participant_id, "trial_id": trial_id, "tick": 3, "kind": "blur",
                          "payload": {"seq": 4}, "created_at": utcnow()})
        seen = await committed(store, trial_id, 10)
        writer.add_tick(tick_row(trial_id, 11))
        await writer.close()
        return seen, await asyncio.to_thread(stored, store, trial_id)

    before_close, after_close = asyncio.run(run())
    assert before_close == list(range(1, 11))
    assert after_close == list(range(1, 12))
    with store.transaction() as session:
        row = session.get(TrialRow, trial_id)
        assert row.ticks == 11
        events = session.query(EventRow).filter_by(trial_id=trial_id).all()
        assert [(e.kind, e.payload) for e in events] == [("blur", {"seq": 4})]


def test_a_bad_row_is_dropped_alone(store, loaded):
    _, trial_id = new_trial(store, loaded)

    async def run() -> None:
        writer = BatchWriter(store, interval=10)
        writer.add_tick(tick_row(trial_id, 1))
        await writer.flush()
        writer.add_tick(tick_row(trial_id, 1))
        writer.add_tick(tick_row(trial_id, 2))
        writer.add_tick(tick_row(trial_id + 999, 1))
        writer.add_tick(tick_row(trial_id, 3))
        await writer.flush()
        assert writer.pending == 0

    asyncio.run(run())
    assert stored(store, trial_id) == [1, 2, 3]
    with store.transaction() as session:
        assert trials.ticks(session, trial_id + 999) == []


def test_a_failed_batch_stays_buffered_and_is_written_later(store, loaded, monkeypatch):
    _, trial_id = new_trial(store, loaded)
    import store.writer as writer_module

    real = writer_module.write_batch
    calls = {"n": 0}

    def flaky(*args: Any) -> None:
        calls["n"] += 1
        if calls["n"] == 1:
            raise ConnectionError("database away")
        real(*args)

    monkeypatch.setattr(writer_module, "write_batch", flaky)

    async def run() -> int:
        writer = BatchWriter(store, interval=10)
        writer.add_tick(tick_row(trial_id, 1))
        with contextlib.suppress(ConnectionError):
            await writer.flush()
        pending = writer.pending
        writer.add_tick(tick_row(trial_id, 2))
        await writer.flush()
        return pending

    assert asyncio.run(run()) == 1
    assert stored(store, trial_id) == [1, 2]


def test_touch_only_moves_activity_forward(store, loaded):
    _, trial_id = new_trial(store, loaded)
    now = utcnow()
    with store.transaction() as session:
        trials.touch(session, trial_id, now + timedelta(seconds=10), ticks=5)
        trials.touch(session, trial_id, now, ticks=3)
    with store.transaction() as session:
        row = session.get(TrialRow, trial_id)
        assert row.last_active_at == now + timedelta(seconds=10) and row.ticks == 5


def test_a_trial_ends_once(store, loaded):
    _participant_id, trial_id = new_trial(store, loaded)
    with store.transaction() as session:
        assert trials.end(session, trial_id, status="finished", reason="delivered", ticks=9, delivered=1, score=20)
        assert not trials.end(session, trial_id, status="abandoned", reason="grace_expired")
    with store.transaction() as session:
        row = session.get(TrialRow, trial_id)
        assert (row.status, row.end_reason, row.ticks, row.score) == ("finished", "delivered", 9, 20)
        assert row.ended_at is not None


def test_a_flush_cut_short_by_shutdown_is_written_once(store, loaded, monkeypatch, caplog):
    """The writer's task is cancelled mid-flush when the server stops, and ``close`` flushes again: the rows
    the cancelled flush was committing are not written a second time (which logged dropped duplicates)."""
    _, trial_id = new_trial(store, loaded)
    import threading

    import store.writer as writer_module

    real = writer_module.write_batch
    writing, release = threading.Event(), threading.Event()
    batches: list[list[int]] = []

    def slow(store_: Any, ticks: Any, events: Any, beats: Any = ()) -> Any:
        batches.append([row["tick"] for row in ticks])
        writing.set()
        release.wait(5)
        return real(store_, ticks, events, beats)

    monkeypatch.setattr(writer_module, "write_batch", slow)

    async def run() -> None:
        writer = BatchWriter(store, interval=10)
        writer.add_tick(tick_row(trial_id, 1))
        flushing = asyncio.create_task(writer.flush())
        await asyncio.to_thread(writing.wait, 5)
        flushing.cancel()
        writer.add_tick(tick_row(trial_id, 2))
        await asyncio.sleep(0.05)
        release.set()
        with contextlib.suppress(asyncio.CancelledError):
            await flushing
        await writer.close()

    with caplog.at_level("WARNING", logger="store.writer"):
        asyncio.run(run())
    assert stored(store, trial_id) == [1, 2]
    assert batches == [[1], [2]]
    assert not caplog.records


def test_a_tick_gets_the_references_gap_from_its_summaries(store, loaded) -> None:
    """The live game's rows carry the reference's state infos in their summaries; the writer stores the
    reference's per-component gap beside them (``ticks.kb_diff``), and NULL for a row without them."""
    from store.tables import TickRow
    from store.writer import write_batch

    _, trial_id = new_trial(store, loaded)
    with_info = tick_row(trial_id, 1) | {
        "kb_summary": {"reference": {"grill": 0, "board": 2, "sink": -1, "robot_held": None}},
        "world_summary": {"reference": {"grill": 1, "board": -1, "sink": -1, "robot_held": "onion"}}}
    write_batch(store, [with_info, tick_row(trial_id, 2)], [])
    with store.transaction() as session:
        stored_rows = {t.tick: t.kb_diff for t in session.query(TickRow).filter_by(trial_id=trial_id)}
    assert stored_rows == {1: {"grill": 1, "board": 1, "sink": 0, "robot_held": 1}, 2: None}
