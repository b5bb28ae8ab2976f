"""The background writer: tick and event rows are buffered in memory and committed in batches.

A batch is committed at least every ``interval`` seconds (default 0.5 s, at most 1 s), so a crash loses at
most the last interval. :meth:`BatchWriter.flush` commits at once (the game loop calls it before ending a
trial, so a finished trial always has all its ticks). A failed batch stays buffered and is retried; rows
that violate a constraint (a tick stored twice) are dropped one by one and logged, never the whole batch.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
from collections.abc import Sequence
from typing import Any

from sqlalchemy import insert
from sqlalchemy.exc import IntegrityError
from sqlalchemy.orm import Session

from planner.summary import kb_diff_of_summaries
from store import trials
from store.engine import Store
from store.tables import EventRow, TickRow

log = logging.getLogger(__name__)
Row = dict[str, Any]


class BatchWriter:
    def __init__(self, store: Store, interval: float = 0.5) -> None:
        self.store = store
        self.interval = interval
        self._ticks: list[Row] = []
        self._events: list[Row] = []
        self._lock = asyncio.Lock()
        self._task: asyncio.Task[None] | None = None
        self.failures = 0

    @property
    def pending(self) -> int:
        return len(self._ticks) + len(self._events)

    def add_tick(self, row: Row) -> None:
        self._ticks.append(row)

    def add_event(self, row: Row) -> None:
        self._events.append(row)

    def start(self) -> None:
        self._task = asyncio.create_task(self._run(), name="batch-writer")

    async def _run(self) -> None:
        """Flush every ``interval`` from the start of the previous flush (a slow write does not stretch
        the interval: the rows a crash can lose stay those of one interval plus one write)."""
        loop = asyncio.get_running_loop()
        next_at = loop.time() + self.interval
        while True:
            await asyncio.sleep(max(next_at - loop.time(), 0.0))
            next_at = max(next_at + self.interval, loop.time())
            try:
                await self.flush()
            except Exception:
                log.exception("store write failed; retrying in %.1f s", self.interval)

    async def flush(self) -> None:
        """Commit everything buffered so far (raises if the database fails; the rows stay buffered)."""
        async with self._lock:
            ticks, events = self._ticks, self._events
            if not ticks and not events:
                return
            self._ticks, self._events = [], []
            write = asyncio.ensure_future(asyncio.to_thread(write_batch, self.store, ticks, events))
            # The thread cannot be stopped: its transaction commits or fails whatever happens to this task, so
            # the rows go back (on failure) when it ends, not when this task is cancelled. Putting them back
            # at the cancel wrote them twice at shutdown (``close`` flushing them again).
            write.add_done_callback(lambda done: self._settle(done, ticks, events))
            try:
                await asyncio.shield(write)
            except asyncio.CancelledError:
                await asyncio.wait({write})
                raise

    def _settle(self, write: asyncio.Future[None], ticks: list[Row], events: list[Row]) -> None:
        """After a finished write: if it failed, put its rows back in front of what came since."""
        if write.cancelled() or write.exception() is not None:
            self.failures += 1
            self._ticks[:0] = ticks
            self._events[:0] = events

    async def close(self) -> None:
        if self._task is not None:
            self._task.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await self._task
            self._task = None
        await self.flush()


def write_batch(store: Store, ticks: Sequence[Row], events: Sequence[Row]) -> None:
    """Insert the rows in one transaction, or row by row when a row violates a constraint. A tick row without a
    ``kb_diff`` gets it from its summaries (:func:`with_kb_diff`)."""
    ticks = [with_kb_diff(row) for row in ticks]
    try:
        with store.transaction() as session:
            _insert(session, ticks, events)
    except IntegrityError:
        log.warning("a batch of %d ticks and %d events violated a constraint; writing row by row",
                    len(ticks), len(events))
        for table, rows in ((TickRow, ticks), (EventRow, events)):
            for row in rows:
                try:
                    with store.transaction() as session:
                        session.execute(insert(table), [row])
                except IntegrityError as exc:
                    log.error("dropped a %s row that violates a constraint: %s", table.__tablename__, exc.orig)
        with store.transaction() as session:
            _touch_trials(session, ticks)


def _insert(session: Session, ticks: Sequence[Row], events: Sequence[Row]) -> None:
    if ticks:
        session.execute(insert(TickRow), list(ticks))
    if events:
        session.execute(insert(EventRow), list(events))
    _touch_trials(session, ticks)


def _touch_trials(session: Session, ticks: Sequence[Row]) -> None:
    latest: dict[int, Row] = {}
    for row in ticks:
        seen = latest.get(row["trial_id"])
        if seen is None or row["tick"] > seen["tick"]:
            latest[row["trial_id"]] = row
    trials.touch_ticks(session, [(trial_id, row["recorded_at"], row["tick"]) for trial_id, row in latest.items()])


def with_kb_diff(row: Row) -> Row:
    """``row`` with ``kb_diff``, the reference's KB gap of the tick from the state infos its KB and world summaries
    carry (``None`` when they carry none)."""
    if row.get("kb_diff") is not None:
        return row
    kb, world = row.get("kb_summary"), row.get("world_summary")
    diff = kb_diff_of_summaries(kb, world) if isinstance(kb, dict) and isinstance(world, dict) else None
    return {**row, "kb_diff": diff}
