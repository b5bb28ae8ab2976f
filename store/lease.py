"""One owner per live round: the lease on a trial row, with a fencing number (docs/deploy.md, "One owner per
round").

A server process that starts or resumes a round **takes** its lease in the transaction that reads the round's
stored state (:func:`take`): ``lease_epoch`` grows by one, so whatever process held it before now holds a stale
epoch. Every tick and trial event carries the epoch it was made under, and the store keeps only rows of the
current one: :func:`admit` locks the trial rows of a batch (``FOR NO KEY UPDATE`` on PostgreSQL; SQLite's
``BEGIN IMMEDIATE`` already serialises writers) and sorts the rows into kept and refused, in the transaction that
inserts them. A takeover and a batch of the old holder thus never interleave: either the batch commits first and
the takeover resumes from it, or the takeover commits first and the batch is refused. Ending a round
(``store.trials.end``) and its robot-health counts (``store.trials.record_health``) are fenced the same way.

The holder renews the lease at every store flush (:func:`renew`, at most ``interval`` apart), writing with it the
round's crash-aware clock (:class:`Beat`): whether the participant is connected (``away_since``), the seconds
the round has run while connected (``connected_s``) and the wait for the participant running now
(``open_wait_s``). A renewal under a stale epoch changes nothing and reports the lease as lost, so a process
that lost a round learns it at its next flush and stops stepping it. ``lease_until`` says until when the holder
is known to be alive (:data:`LEASE_TTL_S` after its last renewal).
"""

from __future__ import annotations

from collections.abc import Collection, Iterable, Mapping, Sequence
from dataclasses import dataclass
from datetime import datetime, timedelta
from typing import Any, cast

from sqlalchemy import Table, bindparam, case, select, update
from sqlalchemy.orm import Session

from store.tables import EventRow, TrialRow
from store.trials import RUNNING
from store.types import utcnow

LEASE_TTL_S = 5.0
"""A lease not renewed for this long is its holder's no more: the holder process is gone (a renewal comes with
every store flush, at most a second apart)."""

Key = tuple[int, int]
"""``(trial_id, epoch)``."""


@dataclass(frozen=True, slots=True)
class Beat:
    """What the holder of a round's lease writes at each renewal."""

    trial_id: int
    epoch: int
    away_since: datetime | None
    """When the participant's connection dropped; ``None`` while connected."""
    connected_s: float
    """Seconds the round has run while the participant was connected."""
    open_wait_s: float | None
    """Seconds of the wait for the participant running now; ``None`` when the world is not waiting."""


def take(session: Session, row: TrialRow, owner: str, now: datetime | None = None) -> int:
    """Take the round's lease for ``owner`` (call with the trial row read in this transaction): the new epoch.
    The participant is connected (``away_since`` cleared); the clock fields stay for the caller to read first."""
    now = now or utcnow()
    session.execute(update(TrialRow).where(TrialRow.id == row.id).values(
        lease_epoch=TrialRow.lease_epoch + 1, lease_owner=owner[:128],
        lease_until=now + timedelta(seconds=LEASE_TTL_S), away_since=None))
    epoch = session.scalar(select(TrialRow.lease_epoch).where(TrialRow.id == row.id))
    return int(epoch or 0)


def fence(session: Session, trial_id: int) -> int:
    """Void the lease of a round about to be ended by someone who does not hold it (the sweep, a reconnection
    after the grace window): whoever held it can store nothing more for it. The new epoch (the end's)."""
    session.execute(update(TrialRow).where(TrialRow.id == trial_id).values(
        lease_epoch=TrialRow.lease_epoch + 1, lease_owner=None))
    return int(session.scalar(select(TrialRow.lease_epoch).where(TrialRow.id == trial_id)) or 0)


def lock(session: Session, trial_ids: Collection[int]) -> dict[int, int]:
    """The current epoch of each trial in ``trial_ids``, their rows locked until the transaction ends (in id
    order, so two processes' batches cannot deadlock)."""
    if not trial_ids:
        return {}
    query = select(TrialRow.id, TrialRow.lease_epoch).where(TrialRow.id.in_(sorted(trial_ids))).order_by(TrialRow.id)
    if session.get_bind().dialect.name == "postgresql":
        query = query.with_for_update(key_share=True)
    return {int(trial_id): int(epoch) for trial_id, epoch in session.execute(query)}


def admit(session: Session, rows: Iterable[Mapping[str, Any]], beats: Iterable[Beat] = ()) -> set[Key]:
    """The ``(trial_id, epoch)`` pairs among ``rows`` (dicts with ``trial_id`` and ``epoch``; rows without an epoch
    are not a round's and always kept) and ``beats`` whose epoch is no longer the trial's: their rows must not be
    stored. Locks the trial rows (:func:`lock`)."""
    wanted: set[Key] = {(int(row["trial_id"]), int(row["epoch"])) for row in rows
                        if row.get("epoch") is not None and row.get("trial_id") is not None}
    wanted |= {(beat.trial_id, beat.epoch) for beat in beats}
    current = lock(session, {trial_id for trial_id, _ in wanted})
    return {(trial_id, epoch) for trial_id, epoch in wanted if current.get(trial_id) != epoch}


def kept(rows: Sequence[dict[str, Any]], stale: set[Key]) -> list[dict[str, Any]]:
    """``rows`` less those of a stale ``(trial_id, epoch)``."""
    if not stale:
        return list(rows)
    return [row for row in rows if row.get("epoch") is None or (row.get("trial_id"), row["epoch"]) not in stale]


def renew(session: Session, beats: Sequence[Beat], now: datetime | None = None) -> None:
    """Renew the leases of ``beats`` (one statement for all) and store each round's clock; a beat whose epoch is
    stale changes nothing (call :func:`admit` first to know which). A connected round's ``last_active_at`` moves
    to ``now`` too (the admin's live list reads it)."""
    if not beats:
        return
    now = now or utcnow()
    table = cast(Table, TrialRow.__table__)
    connected = bindparam("connected_", type_=table.c.last_active_at.type)
    statement = update(table).where(table.c.id == bindparam("trial_id_"),
                                    table.c.lease_epoch == bindparam("epoch_")).values(
        lease_until=bindparam("until_", type_=table.c.lease_until.type),
        away_since=bindparam("away_", type_=table.c.away_since.type),
        connected_s=bindparam("connected_s_"), open_wait_s=bindparam("open_wait_s_"),
        last_active_at=case((table.c.last_active_at < connected, connected), else_=table.c.last_active_at))
    until = now + timedelta(seconds=LEASE_TTL_S)
    session.connection().execute(statement, [
        {"trial_id_": b.trial_id, "epoch_": b.epoch, "until_": until, "away_": b.away_since,
         "connected_s_": round(b.connected_s, 3),
         "open_wait_s_": None if b.open_wait_s is None else round(b.open_wait_s, 3),
         "connected_": now if b.away_since is None else b.away_since} for b in beats])


def release(session: Session, beats: Sequence[Beat], now: datetime | None = None) -> None:
    """Give up the leases of ``beats`` (a server shutting down): their last clock is stored, the participant
    counts as away from ``now`` (if not before), and nobody holds the round until a process takes it. The epoch
    stays, so rows still buffered under it are stored."""
    if not beats:
        return
    now = now or utcnow()
    renew(session, [Beat(b.trial_id, b.epoch, b.away_since or now, b.connected_s, b.open_wait_s) for b in beats],
          now)
    for beat in beats:
        session.execute(update(TrialRow).where(TrialRow.id == beat.trial_id, TrialRow.lease_epoch == beat.epoch)
                        .values(lease_owner=None, lease_until=now))


def holder_alive(row: TrialRow, now: datetime) -> bool:
    """Whether a server process holds the round's lease now (it renewed it within :data:`LEASE_TTL_S`)."""
    return row.lease_owner is not None and row.lease_until is not None and row.lease_until > now


def last_renewal(row: TrialRow) -> datetime | None:
    """When the holder last renewed the lease (``None``: never leased)."""
    return None if row.lease_until is None else row.lease_until - timedelta(seconds=LEASE_TTL_S)


def away_seconds(row: TrialRow, now: datetime) -> float:
    """How long the participant has been away from a running round, for the reconnect grace window: 0 while they
    are connected to the holder; else from when their connection dropped, or (when the holder died with them
    connected) from the holder's last renewal. A server start restarts the count of the rounds nobody holds
    (:func:`restart_count`). Rounds stored before leases count from their last activity."""
    if row.lease_until is None:
        since = row.away_since or row.last_active_at
    elif holder_alive(row, now):
        if row.away_since is None:
            return 0.0
        since = row.away_since
    else:
        since = row.away_since or last_renewal(row) or row.last_active_at
    return max((now - since).total_seconds(), 0.0)


def holders(session: Session, study_ids: Collection[str], now: datetime) -> dict[str, list[int]]:
    """Holder name → the running rounds of ``study_ids`` whose lease it holds now."""
    out: dict[str, list[int]] = {}
    for trial_id, owner in session.execute(select(TrialRow.id, TrialRow.lease_owner).where(
            TrialRow.status == RUNNING, TrialRow.study_id.in_(list(study_ids)), TrialRow.lease_owner.is_not(None),
            TrialRow.lease_until > now)):
        out.setdefault(str(owner), []).append(int(trial_id))
    return out


def expire(session: Session, trial_ids: Collection[int], now: datetime) -> None:
    """End the leases of ``trial_ids`` now: their holder is known to be gone (a process of this machine that no
    longer runs). Their epochs stay."""
    if trial_ids:
        session.execute(update(TrialRow).where(TrialRow.id.in_(list(trial_ids)))
                        .values(lease_owner=None, lease_until=now))


def restart_count(session: Session, study_ids: Collection[str], now: datetime | None = None) -> int:
    """A server process started: the running rounds nobody holds (their process died or shut down) count the
    participant as away from ``now``, so the reconnect grace window starts again (the outage is not theirs). How
    many rounds."""
    now = now or utcnow()
    result = session.execute(update(TrialRow).where(
        TrialRow.status == RUNNING, TrialRow.study_id.in_(list(study_ids)),
        (TrialRow.lease_until.is_(None)) | (TrialRow.lease_until <= now)).values(away_since=now))
    return int(result.rowcount or 0)  # type: ignore[attr-defined]


def recover_wait(session: Session, row: TrialRow, tick: int | None, now: datetime | None = None) -> float | None:
    """The wait for the participant that was running when the round's holder last renewed its lease (it crashed,
    shut down or lost the round since): stored as a ``wait`` event under the holder's epoch (so it enters the idle
    share, ``store.activity``) and cleared on the row. Its seconds, or ``None`` when there was none."""
    seconds = row.open_wait_s
    if seconds is None:
        return None
    if seconds > 0:
        session.add(EventRow(participant_id=row.participant_id, trial_id=row.id, tick=tick, kind="wait",
                             payload={"seconds": round(seconds, 3), "cut_short": True},
                             created_at=now or utcnow(), epoch=row.lease_epoch))
    session.execute(update(TrialRow).where(TrialRow.id == row.id).values(open_wait_s=None))
    return seconds
