"""Read-only summaries for the admin API: how each condition order is filled, participant listings."""

from __future__ import annotations

from datetime import datetime
from typing import Any

from sqlalchemy import func, select
from sqlalchemy.orm import Session

from store.assignment import order_counts
from store.tables import AssignmentRow, ParticipantRow, TrialRow


def order_breakdown(session: Session, study_id: str, n_orders: int, now: datetime,
                    window_minutes: float) -> list[dict[str, int]]:
    """Per order: participants that count for assignment (``counted``, the count assignment itself uses:
    :func:`store.assignment.order_counts`), those who stopped counting (``uncounted``: a round that
    cannot become a cell, a refused device), and all assigned by status/flag; pilot (simulated) participants only
    in ``pilots``, apart from every other number."""
    rows = session.execute(
        select(AssignmentRow.order_index, ParticipantRow.status, ParticipantRow.test_run, ParticipantRow.excluded,
               ParticipantRow.pilot, ParticipantRow.uncounted_reason)
        .join(ParticipantRow, ParticipantRow.id == AssignmentRow.participant_id)
        .where(AssignmentRow.study_id == study_id))
    counted = order_counts(session, study_id, n_orders, now, window_minutes)
    table = [{"index": i, "counted": counted[i], "completed": 0, "in_progress": 0, "screened_out": 0,
              "test_runs": 0, "excluded": 0, "uncounted": 0, "assigned": 0, "pilots": 0} for i in range(n_orders)]
    for index, status, test_run, excluded, pilot, uncounted in rows:
        if not 0 <= index < n_orders:
            continue
        cell = table[index]
        if pilot:
            cell["pilots"] += 1
            continue
        cell["assigned"] += 1
        cell["test_runs"] += int(test_run)
        cell["excluded"] += int(excluded)
        cell["uncounted"] += int(uncounted is not None)
        if status in ("completed", "in_progress", "screened_out"):
            cell[status] += 1
    return table


def participant_public(row: ParticipantRow, order: AssignmentRow | None) -> dict[str, Any]:
    return {
        "participant_id": row.public_id, "study_id": row.study_id, "state": row.state, "status": row.status,
        "step": row.step, "steps": len(row.plan), "order_index": order.order_index if order else None,
        "condition_order": list(order.condition_order) if order else [], "recruiting": row.recruiting,
        "test_run": row.test_run, "pilot": row.pilot, "excluded": row.excluded,
        "exclusion_reason": row.exclusion_reason,
        "created_at": row.created_at.isoformat(),
        "finished_at": row.finished_at.isoformat() if row.finished_at else None,
        "device": row.device, "uncounted_reason": row.uncounted_reason,
        "screen_out_reason": row.screen_out_reason,
    }


def trial_public(row: TrialRow, participant: str | None = None, recruit_id: str | None = None) -> dict[str, Any]:
    """A stored trial for the admin; ``seed`` as text: a 64-bit seed is beyond a JavaScript number's 53 bits of
    precision (``…546`` would show as ``…500``)."""
    return {
        "trial_id": row.id, "study_id": row.study_id, "participant_id": participant, "recruit_id": recruit_id,
        "kind": row.kind,
        "index": row.index, "attempt": row.attempt, "condition": row.condition_id, "kitchen": row.kitchen,
        "robot": row.robot, "view": row.view,
        "fov_angle": row.fov_angle, "seed": str(row.seed), "config_hash": row.config_hash, "status": row.status,
        "end_reason": row.end_reason, "ticks": row.ticks, "delivered": row.delivered, "score": row.score,
        "started_at": row.started_at.isoformat(), "ended_at": row.ended_at.isoformat() if row.ended_at else None,
        "decisions": row.decisions, "missed_decisions": row.missed_decisions,
        "missed_decisions_pct": missed_pct(row.decisions, row.missed_decisions),
        "invalid": row.invalid_reason is not None, "invalid_reason": row.invalid_reason,
        **trial_activity(row),
    }


def trial_activity(row: TrialRow) -> dict[str, Any]:
    """The participant's activity in the trial and its engagement (``store.activity``; ``None`` until the
    trial ended)."""
    return {"selections": row.selections, "interrupts": row.interrupts, "key_actions": row.key_actions,
            "idle_pct": row.idle_pct, "refused_steps": row.refused_steps,
            "delivered_by_participant": row.delivered_by_participant, "delivered_by_robot": row.delivered_by_robot,
            "task_steps": row.task_steps, "robot_task_steps": row.robot_task_steps, "stand_ticks": row.stand_ticks,
            "think_seconds": row.think_seconds,
            "low_engagement": row.engagement_reason is not None, "engagement_reason": row.engagement_reason}


def missed_pct(decisions: int | None, missed: int | None) -> float | None:
    """The share of the robot's decisions that missed their deadline, in % (``None`` when not recorded)."""
    if not decisions or missed is None:
        return None
    return round(100.0 * missed / decisions, 2)


def invalid_trial_counts(session: Session, participant_ids: set[int]) -> dict[int, int]:
    """Participant store id → how many of their trials are marked invalid (only those with any)."""
    return _counts_where(session, participant_ids, TrialRow.invalid_reason.is_not(None))


def low_engagement_counts(session: Session, participant_ids: set[int]) -> dict[int, int]:
    """Participant store id → how many of their trials are low-engagement (only those with any)."""
    return _counts_where(session, participant_ids, TrialRow.engagement_reason.is_not(None))


def _counts_where(session: Session, participant_ids: set[int], condition: Any) -> dict[int, int]:
    if not participant_ids:
        return {}
    rows = session.execute(select(TrialRow.participant_id, func.count())
                           .where(TrialRow.participant_id.in_(participant_ids), condition)
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
