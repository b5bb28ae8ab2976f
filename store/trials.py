"""Trial rows and their stored ticks: create an attempt, end it once, read ticks for replay and resume.

Status is ``running`` until the trial ends: ``finished`` (all orders delivered, or the horizon reached) or
``abandoned`` (the participant did not return within the grace window, or the trial was restarted).
Ending is guarded by ``WHERE status = 'running'``, so a trial ends exactly once.
"""

from __future__ import annotations

from collections.abc import Sequence
from datetime import datetime
from typing import Any, cast

from sqlalchemy import Table, bindparam, case, func, select, update
from sqlalchemy.orm import Session

from store.tables import EventRow, TickRow, TrialRow
from store.types import utcnow
from study_config.study.validity import ABANDONED as ABANDONED  # the statuses, spelled with the rule reading them
from study_config.study.validity import FINISHED as FINISHED
from study_config.study.validity import RUNNING as RUNNING
from study_config.study.views import DEFAULT_VIEW


def create(session: Session, *, study_id: str, participant_id: int, kind: str, index: int, condition_id: str,
           kitchen: str, robot: str, seed: int, config_hash: str, initial_state: dict[str, Any],
           view: str = DEFAULT_VIEW, fov_angle: float | None = None, robot_package: str | None = None,
           robot_version: str | None = None) -> TrialRow:
    """A new running attempt at trial ``(kind, index)`` (attempt = previous attempts + 1); ``robot_package`` and
    ``robot_version``: the distribution that provides its robot (``planner.robot_catalog``)."""
    previous = session.scalar(select(func.max(TrialRow.attempt)).where(
        TrialRow.participant_id == participant_id, TrialRow.kind == kind, TrialRow.index == index)) or 0
    now = utcnow()
    row = TrialRow(study_id=study_id, participant_id=participant_id, kind=kind, index=index,
                   attempt=previous + 1, condition_id=condition_id, kitchen=kitchen, robot=robot, view=view,
                   fov_angle=fov_angle, robot_package=robot_package, robot_version=robot_version,
                   seed=seed,
                   config_hash=config_hash, status=RUNNING, started_at=now, last_active_at=now, ticks=0,
                   delivered=0, score=0, initial_state=initial_state)
    session.add(row)
    session.flush()
    return row


def latest_attempt(session: Session, participant_id: int, kind: str, index: int,
                   lock: bool = False) -> TrialRow | None:
    """The participant's last attempt at trial ``(kind, index)``; with ``lock``, its row locked until the
    transaction ends (where the database can: PostgreSQL)."""
    query = (select(TrialRow)
             .where(TrialRow.participant_id == participant_id, TrialRow.kind == kind, TrialRow.index == index)
             .order_by(TrialRow.attempt.desc()).limit(1))
    if lock:
        query = query.with_for_update(key_share=True).execution_options(populate_existing=True)
    return session.scalar(query)


def end(session: Session, trial_id: int, *, status: str, reason: str, ticks: int | None = None,
        delivered: int | None = None, score: int | None = None, epoch: int | None = None) -> bool:
    """Mark a running trial ``finished`` or ``abandoned``; ``False`` if it had already ended, or if ``epoch`` (the
    ender's lease, ``store.lease``) is no longer the trial's. Without an epoch (the sweep, a restart policy, tools)
    the lease is not asked: call ``store.lease.fence`` too. The lease is given up either way."""
    values: dict[str, Any] = {"status": status, "end_reason": reason, "ended_at": utcnow(), "lease_owner": None,
                              "open_wait_s": None}
    for name, value in (("ticks", ticks), ("delivered", delivered), ("score", score)):
        if value is not None:
            values[name] = value
    where = [TrialRow.id == trial_id, TrialRow.status == RUNNING]
    if epoch is not None:
        where.append(TrialRow.lease_epoch == epoch)
    result = session.execute(update(TrialRow).where(*where).values(**values))
    return bool(result.rowcount)  # type: ignore[attr-defined]


def record_health(session: Session, trial_id: int, *, decisions: int, missed: int,
                  invalid_reason: str | None, failed: int = 0, epoch: int | None = None) -> None:
    """Store the robot's decision counts (late ones, failed ones) and, once set, why the trial is invalid (it is
    never cleared); nothing when ``epoch`` is given and is no longer the trial's lease (another process runs the
    round now)."""
    values: dict[str, Any] = {"decisions": decisions, "missed_decisions": missed, "failed_decisions": failed}
    if invalid_reason is not None:
        values["invalid_reason"] = invalid_reason[:200]
    where = [TrialRow.id == trial_id]
    if epoch is not None:
        where.append(TrialRow.lease_epoch == epoch)
    session.execute(update(TrialRow).where(*where).values(**values))


def robot_invalid(session: Session, trial_id: int) -> bool:
    """Whether the robot's health made trial ``trial_id`` invalid (:func:`record_health`)."""
    return session.scalar(select(TrialRow.invalid_reason).where(TrialRow.id == trial_id)) is not None


def decision_counts(session: Session, trial_id: int) -> tuple[int, int]:
    """``(decisions, missed)`` over the stored ticks of a trial (one robot decision per tick)."""
    row = session.execute(select(func.count(), func.sum(case((TickRow.robot_missed, 1), else_=0)))
                          .where(TickRow.trial_id == trial_id)).one()
    return int(row[0] or 0), int(row[1] or 0)


def failed_count(session: Session, trial_id: int) -> int:
    """The stored ticks of a trial at which the robot failed (``TickRow.robot_error``)."""
    return int(session.scalar(select(func.count()).where(TickRow.trial_id == trial_id,
                                                          TickRow.robot_error.is_not(None))) or 0)


def touch(session: Session, trial_id: int, when: datetime, ticks: int | None = None) -> None:
    """Record activity (a flushed tick, a disconnect) used to judge the reconnect grace window; the time
    only moves forward."""
    values: dict[str, Any] = {
        "last_active_at": case((TrialRow.last_active_at < when, when), else_=TrialRow.last_active_at)}
    if ticks is not None:
        values["ticks"] = case((TrialRow.ticks < ticks, ticks), else_=TrialRow.ticks)
    session.execute(update(TrialRow).where(TrialRow.id == trial_id).values(**values))


def touch_ticks(session: Session, latest: Sequence[tuple[int, datetime, int]]) -> None:
    """:func:`touch` with a tick count for many trials — ``(trial_id, when, ticks)`` — as one statement
    executed for all of them (the writer calls it for every live trial at every flush)."""
    if not latest:
        return
    table = cast(Table, TrialRow.__table__)
    when = bindparam("when_", type_=table.c.last_active_at.type)
    ticks = bindparam("ticks_", type_=table.c.ticks.type)
    statement = update(table).where(table.c.id == bindparam("trial_id_")).values(
        last_active_at=case((table.c.last_active_at < when, when), else_=table.c.last_active_at),
        ticks=case((table.c.ticks < ticks, ticks), else_=table.c.ticks))
    session.connection().execute(statement, [{"trial_id_": t, "when_": w, "ticks_": n} for t, w, n in latest])


def touch_many(session: Session, trial_ids: list[int], when: datetime) -> None:
    for trial_id in trial_ids:
        touch(session, trial_id, when)


def last_tick(session: Session, trial_id: int) -> TickRow | None:
    return session.scalar(select(TickRow).where(TickRow.trial_id == trial_id)
                          .order_by(TickRow.tick.desc()).limit(1))


def ticks(session: Session, trial_id: int, start: int = 0, limit: int = 10_000) -> list[TickRow]:
    return list(session.scalars(select(TickRow).where(TickRow.trial_id == trial_id, TickRow.tick >= start)
                                .order_by(TickRow.tick).limit(limit)))


def events(session: Session, trial_id: int) -> list[EventRow]:
    return list(session.scalars(select(EventRow).where(EventRow.trial_id == trial_id).order_by(EventRow.id)))


def running_of_study(session: Session, study_id: str) -> list[TrialRow]:
    """The running trials of a study (candidates for the grace-window sweep)."""
    return list(session.scalars(select(TrialRow).where(TrialRow.study_id == study_id, TrialRow.status == RUNNING)
                                .order_by(TrialRow.id)))


def list_trials(session: Session, *, participant_id: int | None = None, study_id: str | None = None,
                limit: int = 1000) -> list[TrialRow]:
    query = select(TrialRow).order_by(TrialRow.id.desc()).limit(limit)
    if participant_id is not None:
        query = query.where(TrialRow.participant_id == participant_id)
    if study_id is not None:
        query = query.where(TrialRow.study_id == study_id)
    return list(session.scalars(query))
