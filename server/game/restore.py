"""A trial rebuilt from the store: its fixed facts (:class:`TrialMeta`) and its engine at the last stored tick
(world, modelled KB and the participant's controller), or at tick 0 from the trial's initial state.

Used when a process resumes a trial (its own after a restart, or another process's after that one died) and
when an admin watches a trial that another server process runs (``server.admin.stored_live``).
"""

from __future__ import annotations

from planner.kb import KnowledgeBase, initial_kb
from planner.state import WorldState
from server.flow.service import progress_of
from server.game.controller import ParticipantController
from server.game.engine import TrialEngine
from server.game.meta import TrialMeta
from store.tables import ParticipantRow, TickRow, TrialRow
from study_config.catalog import LoadedStudy


def trial_meta(loaded: LoadedStudy, participant: ParticipantRow, row: TrialRow) -> TrialMeta:
    plan = progress_of(participant).plan
    step = next((s for s in plan if s.kind == "trial" and (s.trial_kind, s.index) == (row.kind, row.index)), None)
    return TrialMeta(trial_id=row.id, attempt=row.attempt, participant_id=participant.id,
                     participant=participant.public_id, study_id=loaded.id, kind=row.kind, index=row.index,
                     number=(step.number or 0) if step else 0, total=(step.total or 0) if step else 0,
                     kind_total=sum(1 for s in plan if s.trial_kind == row.kind),
                     condition=row.condition_id, robot=row.robot, kitchen=row.kitchen, view=row.view,
                     seed=row.seed, test_run=participant.test_run,
                     pilot_pace=participant.pilot_pace if participant.pilot else None, epoch=row.lease_epoch)


def trial_engine(loaded: LoadedStudy, row: TrialRow, last: TickRow | None) -> TrialEngine:
    study = loaded.study
    layout, rules = loaded.layout(row.kitchen), loaded.rules
    angle, delay = study.trial_angle(row.fov_angle), study.world.kb_delay
    blocked = study.timing.blocked_ticks()
    if last is not None:
        return TrialEngine(layout, rules, angle=angle, kb_delay=delay, seed=row.seed,
                           world=WorldState.from_dict(last.world_state), kb=KnowledgeBase.from_dict(last.kb_state),
                           controller=ParticipantController.from_dict(last.controller, layout, rules, angle, blocked))
    world = WorldState.from_dict(row.initial_state)
    return TrialEngine(layout, rules, angle=angle, kb_delay=delay, seed=row.seed, world=world, kb=initial_kb(world),
                       blocked_ticks=blocked)
