"""The server's own numbers, read from the store after a run (never guessed by the clients):

- **tick lateness**: ``ticks.lateness_ms``, the actual start of each world step minus its scheduled start
  (``server.game.live``), p50 / p99 / max over every stored tick of the run;
- **missed ticks**: tick slots that never happened because a step came a whole period or more late (the loop
  does not catch up): the sum over ticks of ``floor(lateness / period)``;
- **robot deadline misses**: ``events`` of kind ``deadline_miss`` (a decision that did not arrive within the
  deadline; the robot stayed that tick), checked against ``ticks.robot_missed``;
- **decision time**: ``ticks.decision_ms`` p50 / p99 (the time the loop waited for the worker's answer);
- **rows written**: every row the run left in the store, per table and in total; server-side ``error`` events.

Ticks and events before ``since`` (the warm-up: the first decisions of a fresh robot worker on a kitchen fill
the planner's caches and take several times longer) are left out of the lateness, missed-tick and deadline
numbers and counted apart (``warmup_*``); rows and errors count the whole run. An ``error`` event with code
``not_playing`` (a choice that crossed the trial's end on the wire) is a race the protocol answers, not a
fault, and is not counted.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from datetime import datetime
from typing import Any

from sqlalchemy import func, select

from store.engine import Store
from store.tables import AnswerRow, AssignmentRow, EventRow, ParticipantRow, TickRow, TrialRow

TABLES = {"participants": ParticipantRow, "assignments": AssignmentRow, "trials": TrialRow, "ticks": TickRow,
          "events": EventRow, "questionnaire_answers": AnswerRow}


def percentile(values: Sequence[float], q: float) -> float | None:
    """The ``q``-quantile (0..1) by the nearest-rank rule; None without values."""
    if not values:
        return None
    ordered = sorted(values)
    rank = max(math.ceil(q * len(ordered)), 1)
    return round(float(ordered[rank - 1]), 2)


def store_metrics(database_url: str, period_ms: float, since: datetime | None = None) -> dict[str, Any]:
    store = Store(database_url)
    try:
        with store.transaction() as session:
            every = session.execute(select(TickRow.lateness_ms, TickRow.decision_ms, TickRow.robot_missed,
                                           TickRow.recorded_at)).all()
            misses = list(session.scalars(select(EventRow.created_at).where(EventRow.kind == "deadline_miss")))
            dict(session.execute(select(EventRow.kind, func.count()).group_by(EventRow.kind)).all())
            rows = {name: int(session.scalar(select(func.count()).select_from(table)) or 0)
                    for name, table in TABLES.items()}
            statuses = dict(session.execute(select(TrialRow.status, func.count()).group_by(TrialRow.status)).all())
            error_payloads = [e.payload for e in session.scalars(select(EventRow).where(EventRow.kind == "error"))]
    finally:
        store.dispose()
    ticks = [t for t in every if since is None or t.recorded_at >= since]
    warm = [t for t in every if since is not None and t.recorded_at < since]
    lateness = [t.lateness_ms for t in ticks]
    decisions = [t.decision_ms for t in ticks if t.decision_ms is not None]
    return {
        "ticks": len(ticks),
        "p50_tick_lateness_ms": percentile(lateness, 0.50),
        "p99_tick_lateness_ms": percentile(lateness, 0.99),
        "max_tick_lateness_ms": round(max(lateness), 2) if lateness else None,
        "missed_ticks": sum(int(v // period_ms) for v in lateness),
        "deadline_misses": sum(1 for at in misses if since is None or at >= since),
        "ticks_robot_missed": sum(1 for t in ticks if t.robot_missed),
        "p50_decision_ms": percentile(decisions, 0.50),
        "p99_decision_ms": percentile(decisions, 0.99),
        "warmup_ticks": len(warm),
        "warmup_p99_tick_lateness_ms": percentile([t.lateness_ms for t in warm], 0.99),
        "warmup_deadline_misses": sum(1 for at in misses if since is not None and at < since),
        "server_error_events": sum(1 for p in error_payloads if p.get("code") != "not_playing"),
        "server_error_samples": [p for p in error_payloads if p.get("code") != "not_playing"][:20],
        "trials": {str(k): int(v) for k, v in statuses.items()},
        "rows": rows,
        "rows_written": sum(rows.values()),
    }
