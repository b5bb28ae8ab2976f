"""Admission control and robot health after a load run, read from the store (the server's own records):

- **waits**: ``events`` of kind ``admission_wait`` (``server.game.admission``), one per participant who found
  the server full: how many, their outcome (admitted, timeout, left) and the waited seconds p50 / p95 / max;
- **robot health**: trials the server marked invalid (``trials.invalid_reason``: more missed robot decisions
  than the study's ``validity.max_missed_decisions_pct``) and the largest share of missed decisions of any
  trial.
"""

from __future__ import annotations

from collections import Counter
from typing import Any

from sqlalchemy import select
from store_metrics import percentile

from store.engine import Store
from store.tables import EventRow, TrialRow


def admission_metrics(database_url: str) -> dict[str, Any]:
    store = Store(database_url)
    try:
        with store.transaction() as session:
            waits = [e.payload for e in session.scalars(select(EventRow).where(EventRow.kind == "admission_wait"))]
            health = session.execute(select(TrialRow.decisions, TrialRow.missed_decisions,
                                            TrialRow.invalid_reason)).all()
    finally:
        store.dispose()
    waited = [float(w.get("waited_s", 0.0)) for w in waits]
    shares = [100.0 * missed / decisions for decisions, missed, _ in health if decisions and missed is not None]
    return {
        "waits": len(waits),
        "wait_outcomes": dict(Counter(str(w.get("outcome")) for w in waits)),
        "p50_wait_s": percentile(waited, 0.50), "p95_wait_s": percentile(waited, 0.95),
        "max_wait_s": round(max(waited), 1) if waited else None,
        "trials_invalid": sum(1 for *_, reason in health if reason),
        "max_missed_decisions_pct": round(max(shares), 2) if shares else None,
    }
