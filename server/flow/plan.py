"""A participant's plan: the fixed list of steps they go through, made once at join and stored with them.

consent → instructions → the comprehension quiz (when the study has one) → practice trial(s) → for each condition of the
assigned order: the trial, then every ``after_each_trial`` questionnaire → the ``end_of_study`` questionnaires → done.

Storing the plan (rather than recomputing it from the study file) keeps a participant's progress stable
if the study file is edited while they take part.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import asdict, dataclass
from typing import Any, Literal

from study_config.study import Study, condition_id

StepKind = Literal["consent", "instructions", "quiz", "trial", "questionnaire", "done"]
TrialKind = Literal["practice", "main"]


@dataclass(frozen=True, slots=True)
class Step:
    """One step. Trial steps name the trial (kind, index within kind, 1-based number of all trials, total,
    condition, robot, kitchen, view, field of view); questionnaire steps the questionnaire and the main trial it follows
    (``None`` for end-of-study questionnaires)."""

    kind: StepKind
    trial_kind: TrialKind | None = None
    index: int | None = None
    number: int | None = None
    total: int | None = None
    condition: str | None = None
    robot: str | None = None
    kitchen: str | None = None
    questionnaire: str | None = None
    after_trial: int | None = None
    view: str | None = None
    """``None`` in plans stored before views existed: those trials are top-down (``DEFAULT_VIEW``)."""
    fov_angle: float | None = None
    """The trial's field of view; ``None`` in plans stored before it was a factor (the study's
    ``world.fov_angle``: :meth:`Study.trial_angle`)."""

    def to_dict(self) -> dict[str, Any]:
        return {k: v for k, v in asdict(self).items() if v is not None}

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Step:
        return cls(**data)


def build_plan(study: Study, order: Sequence[str]) -> tuple[Step, ...]:
    """The steps for a participant assigned ``order`` (condition ids) in ``study``."""
    conditions = {c.id: c for c in study.conditions}
    practice = [(p.kitchen.name, p.robot, study.practice_view(p, order))
                for p in study.practice for _ in range(p.count)]
    practice_angle = study.practice_angle(order)
    total = len(practice) + len(order)
    steps: list[Step] = [Step("consent"), Step("instructions")]
    if study.quiz is not None:
        steps.append(Step("quiz"))
    for i, (kitchen, robot, view) in enumerate(practice):
        steps.append(Step("trial", "practice", i, i + 1, total, condition_id(robot, kitchen), robot, kitchen,
                          view=view, fov_angle=practice_angle))
    after_each = [q.id for q in study.questionnaires if q.when == "after_each_trial"]
    for i, cid in enumerate(order):
        condition = conditions[cid]
        number = len(practice) + i + 1
        steps.append(Step("trial", "main", i, number, total, cid, condition.robot, condition.kitchen,
                          view=condition.view, fov_angle=condition.fov_angle))
        steps += [Step("questionnaire", questionnaire=q, after_trial=i) for q in after_each]
    steps += [Step("questionnaire", questionnaire=q.id) for q in study.questionnaires if q.when == "end_of_study"]
    steps.append(Step("done"))
    return tuple(steps)


def plan_to_json(plan: Sequence[Step]) -> list[dict[str, Any]]:
    return [step.to_dict() for step in plan]


def plan_from_json(data: Sequence[dict[str, Any]]) -> tuple[Step, ...]:
    return tuple(Step.from_dict(item) for item in data)
