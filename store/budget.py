"""Row budgets of participant-writable REST endpoints: what one participant's requests may add to the store
(docs/operations.md §5, "Budgets").

A request that would store an event row (a device report, a refused join naming the participant's recruiting id)
stores it while the participant has fewer than ``limit`` rows of that kind from the last ``window``; past that it
is **counted, not stored**: the latest stored row of the kind carries the count in its payload (``dropped``), so a
flood adds no row and the store still says how many were refused. The budget is read from the store in the
request's own transaction, so it holds across server processes. (The game websocket's messages have their own
per-trial budget: ``server/game/budget.py``.)
"""

from __future__ import annotations

from dataclasses import dataclass
from datetime import datetime, timedelta

from sqlalchemy import func, select
from sqlalchemy.orm import Session

from store.tables import EventRow
from store.types import utcnow


@dataclass(frozen=True, slots=True)
class RowBudget:
    limit: int
    window: timedelta


DEVICE_REPORTS = RowBudget(20, timedelta(hours=1))
"""``device_check`` rows per participant: the browser reports its device once per page load (and when asked to
check again); twenty loads an hour is far above any participant's."""
REFUSED_JOINS = RowBudget(20, timedelta(hours=1))
"""``join_refused`` rows per participant whose recruiting id others try (a refused join names the id's owner)."""


def store_or_count(session: Session, row: EventRow, budget: RowBudget, now: datetime | None = None) -> bool:
    """Add ``row`` (an event of a participant) if its participant's budget of its kind allows; else count it on
    the latest stored row of the kind (``payload.dropped``). Whether it was stored."""
    now = now or utcnow()
    used = session.scalar(select(func.count()).select_from(EventRow).where(
        EventRow.participant_id == row.participant_id, EventRow.kind == row.kind,
        EventRow.created_at >= now - budget.window)) or 0
    if used < budget.limit:
        session.add(row)
        return True
    query = (select(EventRow).where(EventRow.participant_id == row.participant_id, EventRow.kind == row.kind)
             .order_by(EventRow.id.desc()).limit(1))
    if session.get_bind().dialect.name == "postgresql":
        query = query.with_for_update()
    latest = session.scalar(query)
    if latest is not None:
        payload = dict(latest.payload or {})
        payload["dropped"] = int(payload.get("dropped", 0)) + 1
        latest.payload = payload
    return False
