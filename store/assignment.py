"""Condition-order assignment: the least-filled order, decided inside the joining transaction.

An order's fill is the number of its participants that count: not test runs, not excluded, still counting
(``participants.uncounted_reason`` empty: every main round can still become an analysable cell and the device was not
refused; the rule lives in :mod:`server.flow.standing`), and either completed, or still in progress and joined within
the study's ``in_progress_window_minutes``. Screened-out participants never count. Ties go to the lowest order index.
Pilot (simulated) participants are balanced among themselves: they never count for real participants, and real ones
never count for pilots.

Atomicity: the count and the insert happen in one transaction that first serialises with every other
join of the same study — on PostgreSQL by locking the study's row (``SELECT ... FOR UPDATE``), on SQLite by
``BEGIN IMMEDIATE`` (see :mod:`store.engine`). So simultaneous joins, from any number of server
processes sharing the database, see each other's assignments and stay balanced (max − min ≤ 1).
"""

from __future__ import annotations

from datetime import datetime, timedelta

from sqlalchemy import and_, func, or_, select
from sqlalchemy.orm import Session

from store.tables import AssignmentRow, ParticipantRow, StudyRow


def lock_study(session: Session, study_id: str) -> None:
    """Serialise with other joins of ``study_id`` until the transaction ends (a no-op beyond
    ``BEGIN IMMEDIATE`` on SQLite)."""
    query = select(StudyRow.id).where(StudyRow.id == study_id)
    if session.get_bind().dialect.name == "postgresql":
        query = query.with_for_update()
    if session.scalar(query) is None:
        raise LookupError(f"unknown study {study_id!r}")


def order_counts(session: Session, study_id: str, n_orders: int, now: datetime,
                 window_minutes: float, pilot: bool = False) -> list[int]:
    """How many counting participants each order has (see the module docstring); with ``pilot``, how many
    counting pilot participants."""
    since = now - timedelta(minutes=window_minutes)
    query = (
        select(AssignmentRow.order_index, func.count())
        .join(ParticipantRow, ParticipantRow.id == AssignmentRow.participant_id)
        .where(
            AssignmentRow.study_id == study_id,
            ParticipantRow.test_run.is_(False),
            ParticipantRow.pilot.is_(pilot),
            ParticipantRow.excluded.is_(False),
            ParticipantRow.uncounted_reason.is_(None),
            or_(ParticipantRow.status == "completed",
                and_(ParticipantRow.status == "in_progress", ParticipantRow.created_at >= since)),
        )
        .group_by(AssignmentRow.order_index)
    )
    counts = [0] * n_orders
    for index, count in session.execute(query):
        if 0 <= index < n_orders:
            counts[index] = count
    return counts


def least_filled(counts: list[int]) -> int:
    """The index of the smallest count (the lowest index among equals)."""
    return min(range(len(counts)), key=lambda i: (counts[i], i))
