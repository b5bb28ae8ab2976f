"""The background writer: tick and event rows are buffered in memory and committed in batches.

A batch is committed at least every ``interval`` seconds (default 0.5 s, at most 1 s), so a crash loses at
most the last interval. :meth:`BatchWriter.flush` commits at once (the game loop calls it before ending a
trial, so a finished trial always has all its ticks). A failed batch stays buffered and is retried; rows
that violate a constraint (a tick stored twice) are dropped one by one and logged, never the whole batch.

Rows of a live round carry its lease epoch (``store.lease``): the batch's transaction keeps only those of each
trial's current epoch and counts the rest (``refused``). Each flush also renews the leases this process holds
(the :class:`~store.lease.Beat` of each live round, from ``beats``), in the same transaction, and tells
``on_stale`` which ``(trial_id, epoch)`` it no longer holds, so that the process stops stepping those rounds.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
from collections.abc import Callable, Sequence
from typing import Any

from sqlalchemy import insert
from sqlalchemy.exc import IntegrityError
from sqlalchemy.orm import Session

from planner.summary import kb_diff_of_summaries
from store import lease, trials
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
        self.refused = 0
        """Rows refused because their round's lease had passed to another process (never stored)."""
        self.beats: Callable[[], list[lease.Beat]] = list
        """The leases this process holds, renewed at every flush (the game registry sets it)."""
        self.on_stale: Callable[[set[lease.Key]], None] = lambda stale: None
        """Told the ``(trial_id, epoch)`` leases found lost at a flush (the game registry sets it)."""

    @property
    def pending(self) -> int:
        return len(self._ticks) + len(self._events)

    def add_tick(self, row: Row) -> None:
        row.setdefault("epoch", None)
        self._ticks.append(row)

    def add_event(self, row: Row) -> None:
        """Buffer an event row (``epoch``: the round's lease epoch, for a live round's events)."""
        row.setdefault("epoch", None)
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
        """Commit everything buffered so far and renew the leases held (raises if the database fails; the rows
        stay buffered)."""
        async with self._lock:
            ticks, events, beats = self._ticks, self._events, self.beats()
            if not ticks and not events and not beats:
                return
            self._ticks, self._events = [], []
            write = asyncio.ensure_future(asyncio.to_thread(write_batch, self.store, ticks, events, beats))
            # The thread cannot be stopped: its transaction commits or fails whatever happens to this task, so
            # the rows go back (on failure) when it ends, not when this task is cancelled. Putting them back
            # at the cancel wrote them twice at shutdown (``close`` flushing them again).
            write.add_done_callback(lambda done: self._settle(done, ticks, events))
            try:
                await asyncio.shield(write)
            except asyncio.CancelledError:
                await asyncio.wait({write})
                raise

    def _settle(self, write: asyncio.Future[Written], ticks: list[Row], events: list[Row]) -> None:
        """After a finished write: if it failed, put its rows back in front of what came since; else report the
        leases found lost."""
        if write.cancelled() or write.exception() is not None:
            self.failures += 1
            self._ticks[:0] = ticks
            self._events[:0] = events
            return
        written = write.result()
        if written.refused:
            self.refused += written.refused
            log.warning("refused %d row(s) of round(s) another server process took over: %s", written.refused,
                        ", ".join(f"trial {t} epoch {e}" for t, e in sorted(written.stale)))
        if written.stale:
            self.on_stale(written.stale)

    async def close(self) -> None:
        if self._task is not None:
            self._task.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await self._task
            self._task = None
        await self.flush()


class Written:
    """What a batch's write found: the leases no longer held, and how many rows it refused for that."""

    def __init__(self) -> None:
        self.stale: set[lease.Key] = set()
        self.refused = 0


def write_batch(store: Store, ticks: Sequence[Row], events: Sequence[Row],
                beats: Sequence[lease.Beat] = ()) -> Written:
    """Insert the rows of the current lease epochs and renew the leases of ``beats``, in one transaction, or row
    by row when a row violates a constraint. A tick row without a ``kb_diff`` gets it from its summaries
    (:func:`with_kb_diff`)."""
    ticks = [with_kb_diff(row) for row in ticks]
    written = Written()
    try:
        with store.transaction() as session:
            _insert(session, ticks, events, beats, written)
    except IntegrityError:
        log.warning("a batch of %d ticks and %d events violated a constraint; writing row by row",
                    len(ticks), len(events))
        written = Written()
        for table, rows in ((TickRow, ticks), (EventRow, events)):
            for row in rows:
                try:
                    with store.transaction() as session:
                        stale = lease.admit(session, [row])
                        written.stale |= stale
                        if stale:
                            written.refused += 1
                        else:
                            session.execute(insert(table), [row])
                except IntegrityError as exc:
                    log.error("dropped a %s row that violates a constraint: %s", table.__tablename__, exc.orig)
        with store.transaction() as session:
            _insert(session, (), (), beats, written)
            _touch_trials(session, lease.kept(list(ticks), written.stale))
    return written


def _insert(session: Session, ticks: Sequence[Row], events: Sequence[Row], beats: Sequence[lease.Beat],
            written: Written) -> None:
    stale = lease.admit(session, [*ticks, *events], beats)
    written.stale |= stale
    if stale:
        kept_ticks, kept_events = lease.kept(list(ticks), stale), lease.kept(list(events), stale)
        written.refused += len(ticks) - len(kept_ticks) + len(events) - len(kept_events)
        ticks, events = kept_ticks, kept_events
    lease.renew(session, [b for b in beats if (b.trial_id, b.epoch) not in stale])
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
