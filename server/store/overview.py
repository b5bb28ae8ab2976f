"""Read-only summaries for the admin API: how each condition order is filled, participant listings."""

from __future__ import annotations

from datetime import datetime, timedelta
from typing import Any

from sqlalchemy import func, select
from sqlalchemy.orm import Session

from server.store.tables import AssignmentRow, ParticipantRow, TrialRow


def order_breakdown(session: Session, study_id: str, n_orders: int, now: datetime,
                    window_minutes: float) -> list[dict[str, int]]:
    """Per order: participants that count for assignment (``counted``), and all assigned by status/flag; pilot
    (simulated) participants only in ``pilots``, apart from every other number."""
    since = now - timedelta(minutes=window_minutes)
    rows = session.execute(
        select(AssignmentRow.order_index, ParticipantRow.status, ParticipantRow.test_run, ParticipantRow.excluded,
               ParticipantRow.created_at, ParticipantRow.pilot)
        .join(ParticipantRow, ParticipantRow.id == AssignmentRow.participant_id)
        .where(AssignmentRow.study_id == study_id))
    table = [{"index": i, "counted": 0, "completed": 0, "in_progress": 0, "screened_out": 0, "test_runs": 0,
              "excluded": 0, "assigned": 0, "pilots": 0} for i in range(n_orders)]
    for index, status, test_run, excluded, created, pilot in rows:
        if not 0 <= index < n_orders:
            continue
        cell = table[index]
        if pilot:
            cell["pilots"] += 1
            continue
        cell["assigned"] += 1
        cell["test_runs"] += int(test_run)
        cell["excluded"] += int(excluded)
        if status in ("completed", "in_progress", "screened_out"):
            cell[status] += 1
        if not test_run and not excluded and (
                status == "completed" or (status == "in_progress" and created >= since)):
            cell["counted"] += 1
    return table


def participant_public(row: ParticipantRow, order: AssignmentRow | None) -> dict[str, Any]:
    return {
        "participant_id": row.public_id, "study_id": row.study_id, "state": row.state, "status": row.status,
        "step": row.step, "steps": len(row.plan), "order_index": order.order_index if order else None,
        "condition_order": list(order.condition_order) if order else [], "recruiting": row.recruiting,
        "test_run": row.test_run, "pilot": row.pilot, "excluded": row.excluded, "exclusion_reason": row.exclusion_reason,
        "created_at": row.created_at.isoformat(),
        "finished_at": row.finished_at.isoformat() if row.finished_at else None,
        "device": row.device,
    }


def trial_public(row: TrialRow, participant: str | None = None, recruit_id: str | None = None) -> dict[str, Any]:
    """A stored trial for the admin; ``seed`` as text: a 64-bit seed is beyond a JavaScript number's 53 bits of
    precision (``…546`` would show as ``…500``)."""
    return {
        "trial_id": row.id, "study_id": row.study_id, "participant_id": participant, "recruit_id": recruit_id,
        "kind": row.kind,
        "index": row.index, "attempt": row.attempt, "condition": row.condition_id, "kitchen": row.kitchen,
        "robot": row.robot, "view": row.view, "seed": str(row.seed), "config_hash": row.config_hash, "status": row.status,
        "end_reason": row.end_reason, "ticks": row.ticks, "delivered": row.delivered, "score": row.score,
        "started_at": row.started_at.isoformat(), "ended_at": row.ended_at.isoformat() if row.ended_at else None,
        "decisions": row.decisions, "missed_decisions": row.missed_decisions,
        "missed_decisions_pct": missed_pct(row.decisions, row.missed_decisions),
        "invalid": row.invalid_reason is not None, "invalid_reason": row.invalid_reason,
    }


def missed_pct(decisions: int | None, missed: int | None) -> float | None:
    """The share of the robot's decisions that missed their deadline, in % (``None`` when not recorded)."""
    if not decisions or missed is None:
        return None
    return round(100.0 * missed / decisions, 2)


def invalid_trial_counts(session: Session, participant_ids: set[int]) -> dict[int, int]:
    """Participant store id → how many of their trials are marked invalid (only those with any)."""
    if not participant_ids:
        return {}
    rows = session.execute(select(TrialRow.participant_id, func.count())
                           .where(TrialRow.participant_id.in_(participant_ids), TrialRow.invalid_reason.is_not(None))
                           .group_by(TrialRow.participant_id))
    return {pid: int(count) for pid, count in rows}


def participant_names(session: Session, participant_ids: set[int]) -> dict[int, tuple[str, str | None]]:
    """Store id → (public id, recruiting id): the admin lists show the recruiting id (what the experimenter
    sees on the recruiting platform) with the public id beside it."""
    if not participant_ids:
        return {}
    rows = session.execute(select(ParticipantRow.id, ParticipantRow.public_id, ParticipantRow.recruit_id)
                           .where(ParticipantRow.id.in_(participant_ids)))
    return {pid: (public, recruit) for pid, public, recruit in rows}
