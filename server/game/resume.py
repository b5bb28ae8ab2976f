"""Starting or resuming the trial a participant's current step asks for (one transaction).

- No running attempt: a new attempt starts at tick 0 with a fresh seed.
- A running attempt inactive for at most the study's ``reconnect.grace_seconds`` (counted from its last
  stored activity: the last flushed tick, a disconnect, a server shutdown): it resumes from its last
  stored tick — world, modelled KB and the participant's subtask — so after a crash at most the unflushed
  last second is replayed, and no tick is stored twice (ticks are keyed by ``(trial_id, tick)``).
- Inactive for longer, per ``reconnect.after_grace``: ``resume`` as above; ``restart`` marks the attempt
  abandoned (reason ``restarted``) and starts a new attempt at tick 0; ``abandon`` marks it abandoned
  (reason ``grace_expired``) and moves the participant to their next step.

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
from store import trials
from store.engine import Store
from store.tables import ParticipantRow, TickRow, TrialRow
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


class StepPassed(Exception):
    """The participant is no longer at the step asked for: its trial ended after the caller read the step."""

    def __init__(self, progress: Progress) -> None:
        super().__init__(f"the participant has moved on to {progress.phase.value}")
        self.progress = progress


def prepare_trial(store: Store, loaded: LoadedStudy, participant_id: int, step: Step) -> Prepared:
    if step.kind != "trial" or step.trial_kind is None or step.index is None:
        raise ValueError("the participant's current step is not a trial")
    study = loaded.study
    with store.transaction() as session:
        participant = session.get(ParticipantRow, participant_id, with_for_update=True, populate_existing=True)
        if participant is None:
            raise ValueError(f"no participant {participant_id}")
        progress = service.progress_of(participant)
        if progress.current != step:
            raise StepPassed(progress)
        row = trials.latest_attempt(session, participant_id, step.trial_kind, step.index)
        if row is None or row.status != trials.RUNNING:
            return Prepared("new", _create(session, loaded, participant_id, step))
        outcome = on_return(row.last_active_at, utcnow(), study.reconnect)
        if outcome == "resume":
            decisions, missed = trials.decision_counts(session, row.id)
            return Prepared("resume", row, trials.last_tick(session, row.id), decisions=decisions, missed=missed,
                            failed=trials.failed_count(session, row.id))
        if outcome == "restart":
            trials.end(session, row.id, status=trials.ABANDONED, reason="restarted")
            return Prepared("new", _create(session, loaded, participant_id, step))
        moved = service.end_trial_in(session, participant_id, row.id, step.trial_kind, step.index,
                                     status=trials.ABANDONED, reason="grace_expired", study=study)
        return Prepared("abandoned", row, progress=moved)


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
    """Abandon running trials of an ``abandon``-policy study idle for more than ``idle_seconds`` and not
    live in this process (left by a crashed server or a participant who never came back); each participant
    moves to their next step. Returns how many were abandoned."""
    if loaded.study.reconnect.after_grace != "abandon":
        return 0
    before = utcnow() - timedelta(seconds=idle_seconds)
    count = 0
    with store.transaction() as session:
        for row in trials.running_inactive_since(session, loaded.id, before):
            if row.id in live:
                continue
            if service.end_trial_in(session, row.participant_id, row.id, row.kind, row.index,
                                    status=trials.ABANDONED, reason="grace_expired",
                                    study=loaded.study) is not None:
                count += 1
    return count
