"""Starting or resuming the trial a participant's current step asks for (one transaction), and taking its lease.

- No running attempt: a new attempt starts at tick 0 with a fresh seed.
- A running attempt whose participant has been away for at most the study's ``reconnect.grace_seconds``
  (``store.lease.away_seconds``: 0 while they are connected to another process; else from when their connection
  dropped, or from when that process died; a server start restarts the count): it resumes from its last stored
  tick — world, modelled KB and the participant's subtask — so after a crash at most the unflushed last flush is
  replayed, and no tick is stored twice (ticks are keyed by ``(trial_id, tick)``).
- Away for longer, per ``reconnect.after_grace``: ``resume`` as above; ``restart`` marks the attempt
  abandoned (reason ``restarted``) and starts a new attempt at tick 0; ``abandon`` marks it abandoned
  (reason ``grace_expired``) and moves the participant to their next step.

Whatever the outcome, this process takes the round's lease in the same transaction (``store.lease.take``): if
another process ran it, that process's later ticks and its end are refused, and it stops stepping the round at its
next store flush (docs/deploy.md, "One owner per round"). The round's clock goes on from what the lease stored: the
seconds it ran while connected (its ``timing.max_round_seconds``), and the wait for the participant running when
its last holder stopped is stored as a ``wait`` event (it enters the idle share).

The step is checked against the participant's progress in the same transaction (their row locked where the
database can): a caller that read it just before the trial ended (a reconnection racing the trial's last tick)
gets :class:`StepPassed`, not a second attempt of a trial already played.
"""

from __future__ import annotations

import secrets
from dataclasses import dataclass
from datetime import timedelta
from typing import Literal

from sqlalchemy.orm import Session

from planner import robot_catalog
from planner.state import WorldState, initial_state
from server.flow import service
from server.flow.plan import Step
from server.flow.progress import Progress
from server.flow.rounds import on_return
from store import lease, trials
from store.engine import Store
from store.tables import EventRow, ParticipantRow, TickRow, TrialRow
from store.types import utcnow
from study_config.catalog import LoadedStudy
from study_config.study.views import DEFAULT_VIEW

Outcome = Literal["new", "resume", "abandoned"]


@dataclass(frozen=True)
class Prepared:
    outcome: Outcome
    trial: TrialRow
    last_tick: TickRow | None = None
    progress: Progress | None = None
    """The participant's progress after an abandonment."""
    decisions: int = 0
    missed: int = 0
    """Robot decisions made and missed so far (from the stored ticks of a resumed trial)."""
    failed: int = 0
    """Of these, the ones the robot failed."""
    epoch: int = 0
    """The lease epoch taken (``store.lease``)."""
    previous_owner: str | None = None
    """The process that held the round's lease before (``None``: none, or a new round)."""
    round_seconds: float = 0.0
    """Seconds the round has run while the participant was connected (its wall-clock limit's count so far)."""


class StepPassed(Exception):
    """The participant is no longer at the step asked for: its trial ended after the caller read the step."""

    def __init__(self, progress: Progress) -> None:
        super().__init__(f"the participant has moved on to {progress.phase.value}")
        self.progress = progress


def prepare_trial(store: Store, loaded: LoadedStudy, participant_id: int, step: Step, owner: str = "") -> Prepared:
    """``owner``: this process's name (``host:pid``), the lease's holder from now on."""
    if step.kind != "trial" or step.trial_kind is None or step.index is None:
        raise ValueError("the participant's current step is not a trial")
    study = loaded.study
    with store.transaction() as session:
        # FOR NO KEY UPDATE (PostgreSQL): a store batch inserting this participant's rows (its foreign keys take FOR
        # KEY SHARE) goes on meanwhile, so it cannot deadlock with this transaction over the trial row below.
        participant = session.get(ParticipantRow, participant_id, with_for_update={"key_share": True},
                                  populate_existing=True)
        if participant is None:
            raise ValueError(f"no participant {participant_id}")
        progress = service.progress_of(participant)
        if progress.current != step:
            raise StepPassed(progress)
        row = trials.latest_attempt(session, participant_id, step.trial_kind, step.index, lock=True)
        if row is None or row.status != trials.RUNNING:
            return _new(session, loaded, participant_id, step, owner)
        now = utcnow()
        last = trials.last_tick(session, row.id)
        lease.recover_wait(session, row, last.tick if last is not None else 0, now)
        outcome = on_return(lease.away_seconds(row, now), study.reconnect)
        if outcome == "resume":
            previous = row.lease_owner
            spent = max(row.connected_s or 0.0, (last.round_seconds or 0.0) if last is not None else 0.0)
            epoch = lease.take(session, row, owner, now)
            decisions, missed = trials.decision_counts(session, row.id)
            return Prepared("resume", row, last, decisions=decisions, missed=missed,
                            failed=trials.failed_count(session, row.id), epoch=epoch, previous_owner=previous,
                            round_seconds=spent)
        if outcome == "restart":  # the attempt ends, the participant stays at the step for a new one
            epoch = lease.fence(session, row.id)
            if trials.end(session, row.id, status=trials.ABANDONED, reason="restarted", epoch=epoch):
                session.add(EventRow(participant_id=participant_id, trial_id=row.id, tick=row.ticks, kind="trial_end",
                                     payload={"status": trials.ABANDONED, "reason": "restarted", "ticks": row.ticks},
                                     created_at=now, epoch=epoch))
            return _new(session, loaded, participant_id, step, owner)
        moved = service.end_trial_in(session, participant_id, row.id, step.trial_kind, step.index,
                                     status=trials.ABANDONED, reason="grace_expired", study=study, ticks=row.ticks,
                                     end_event={"status": trials.ABANDONED, "reason": "grace_expired",
                                                "ticks": row.ticks})
        return Prepared("abandoned", row, progress=moved)


def _new(session: Session, loaded: LoadedStudy, participant_id: int, step: Step, owner: str) -> Prepared:
    row = _create(session, loaded, participant_id, step)
    return Prepared("new", row, epoch=lease.take(session, row, owner))


def _create(session: Session, loaded: LoadedStudy, participant_id: int, step: Step) -> TrialRow:
    if step.kitchen is None or step.robot is None or step.condition is None:
        raise ValueError(f"trial step without kitchen, robot or condition: {step}")
    world: WorldState = initial_state(loaded.layout(step.kitchen), loaded.rules)
    robot = robot_catalog.entry(loaded.planner(step.robot))
    return trials.create(session, study_id=loaded.id, participant_id=participant_id, kind=str(step.trial_kind),
                         index=int(step.index or 0), condition_id=step.condition, kitchen=step.kitchen,
                         robot=step.robot, view=step.view or DEFAULT_VIEW,
                         fov_angle=loaded.study.trial_angle(step.fov_angle), seed=secrets.randbits(62),
                         config_hash=loaded.study.config_hash(), robot_package=robot.package,
                         robot_version=robot.version, initial_state=world.to_dict())


def abandon_stale(store: Store, loaded: LoadedStudy, idle_seconds: float, live: set[int]) -> int:
    """Abandon running trials of an ``abandon``-policy study whose participant has been away for more than
    ``idle_seconds`` (``store.lease.away_seconds``) and that no live process holds (left by a crashed server or a
    participant who never came back; a live holder applies the grace window itself); each participant moves to
    their next step. Returns how many were abandoned."""
    if loaded.study.reconnect.after_grace != "abandon":
        return 0
    now = utcnow()
    before = now - timedelta(seconds=idle_seconds)
    count = 0
    with store.transaction() as session:
        for row in trials.running_of_study(session, loaded.id):
            if row.id in live or lease.holder_alive(row, now) or lease.away_seconds(row, now) <= idle_seconds:
                continue
            if row.lease_until is None and row.last_active_at >= before:
                continue
            last = trials.last_tick(session, row.id)
            lease.recover_wait(session, row, last.tick if last is not None else 0, now)
            if service.end_trial_in(session, row.participant_id, row.id, row.kind, row.index,
                                    status=trials.ABANDONED, reason="grace_expired", study=loaded.study,
                                    ticks=row.ticks, end_event={"status": trials.ABANDONED,
                                                                "reason": "grace_expired",
                                                                "ticks": row.ticks}) is not None:
                count += 1
    return count
