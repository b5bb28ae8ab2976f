"""What ``GET /api/session`` answers: the participant's state and what to show next.

Never the condition's robot or kitchen names beyond the assigned order given at join: the pages show
"round 2 of 5", not which robot is playing. ``fov_angle`` (the study's field of view, the same in every trial)
lets the instructions draw the cone the participant will have; a trial's ``view`` (top-down or first-person)
lets the round's intro card explain its controls (the participant sees the view anyway).
"""

from __future__ import annotations

from typing import Any

from server.catalog import LoadedStudy
from server.flow.progress import Phase
from server.flow.service import completion, progress_of
from server.store.tables import AssignmentRow, ParticipantRow
from server.study.views import DEFAULT_VIEW


def session_view(loaded: LoadedStudy, row: ParticipantRow, order: AssignmentRow | None) -> dict[str, Any]:
    progress = progress_of(row)
    phase = progress.phase
    step = progress.current
    study = loaded.study
    trial_steps = [s for s in progress.plan if s.kind == "trial"]
    done = sum(1 for s in progress.plan[: progress.step] if s.kind == "trial")
    view: dict[str, Any] = {
        "participant_id": row.public_id,
        "study_id": row.study_id,
        "state": phase.value,
        "step": progress.step,
        "steps": len(progress.plan),
        "trials_done": done,
        "trials_total": len(trial_steps),
        "order_index": order.order_index if order else None,
        "condition_order": list(order.condition_order) if order else [],
        "test_run": row.test_run,
        "fov_angle": study.world.fov_angle,
    }
    if phase is Phase.CONSENT:
        view["consent"] = study.consent
    elif phase is Phase.INSTRUCTIONS:
        view["instructions"] = study.instructions
    elif phase in (Phase.PRACTICE, Phase.TRIAL):
        view["trial"] = {"kind": step.trial_kind, "index": step.index, "number": step.number,
                         "total": step.total, "kind_number": (step.index or 0) + 1,
                         "kind_total": sum(1 for s in progress.plan if s.trial_kind == step.trial_kind),
                         "view": step.view or DEFAULT_VIEW, "websocket": "/ws/play"}
    elif phase is Phase.QUESTIONNAIRE:
        questionnaire = next(q for q in study.questionnaires if q.id == step.questionnaire)
        view["questionnaire"] = {
            "id": questionnaire.id, "title": questionnaire.title, "after_trial": step.after_trial,
            "items": [{"id": i.id, "text": i.text, "required": i.required,
                       "scale": {"min": i.scale.min, "max": i.scale.max,
                                 "labels": {str(k): v for k, v in i.scale.labels.items()}}}
                      for i in questionnaire.items],
        }
    if phase in (Phase.DONE, Phase.SCREENED_OUT):
        view["completion"] = completion(loaded, row)
    return view
