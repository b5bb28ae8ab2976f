"""What ``GET /api/session`` answers: the participant's state and what to show next.

Never a condition, robot, kitchen or the participant's condition order (nor its index): the pages show "round 2 of
5", not which robot is playing (blinding, ``docs/protocol.md`` §1). ``fov_angle`` (the field of view of the
participant's current, else first, trial: the study's one angle, or their group's with ``fov_angle`` a factor) lets
the instructions draw the cone the participant will have; a trial's ``view`` (top-down
or first-person) lets the round's intro card explain its controls (the participant sees the view anyway). Consent
and instructions have their duration placeholders filled in from the study (:mod:`study_config.study.duration`),
counting the participant's own rounds. A participant screened out for not taking part is told the rule, the
measured value and the round (``completion.detail``), so the end page states their actual reason.
"""

from __future__ import annotations

from typing import Any

from sqlalchemy import select
from sqlalchemy.orm import Session

from server.flow import payment
from server.flow.plan import Step
from server.flow.progress import Phase
from server.flow.rounds import RoundFacts, round_facts
from server.flow.service import completion, progress_of, quiz_attempts
from store.tables import EventRow, ParticipantRow
from store.types import utcnow
from study_config.catalog import LoadedStudy
from study_config.study import Study
from study_config.study.device import DeviceRequirements
from study_config.study.duration import fill_placeholders, study_length
from study_config.study.questionnaire import Item
from study_config.study.views import DEFAULT_VIEW


def load_session_view(session: Session, loaded: LoadedStudy, participant_id: int,
                      connected: frozenset[int] = frozenset()) -> dict[str, Any]:
    """The session view of the participant, read in ``session``'s transaction; ``connected``: the trials a
    participant is connected to in this process (:func:`server.flow.rounds.round_facts`)."""
    row = session.get(ParticipantRow, participant_id)
    if row is None:
        raise LookupError(participant_id)
    progress = progress_of(row)
    facts = round_facts(session, participant_id, progress, utcnow(), loaded.study.reconnect, connected)
    attempts = quiz_attempts(session, participant_id) if progress.phase is Phase.QUIZ else 0
    detail = screen_out_detail(session, participant_id) if progress.phase is Phase.SCREENED_OUT else None
    return session_view(loaded, row, facts, attempts, detail)


def screen_out_detail(session: Session, participant_id: int) -> dict[str, Any] | None:
    """What the end page says of a round the participant did not take part in: the last ``trial_low_engagement``
    event's rule, measured value, limit and round (``None`` without one, e.g. a trial stored before they were)."""
    found = session.scalars(select(EventRow).where(EventRow.participant_id == participant_id,
                                                   EventRow.kind == "trial_low_engagement")
                            .order_by(EventRow.id.desc()).limit(1)).first()
    if found is None or "rule" not in (found.payload or {}):
        return None
    return {k: found.payload.get(k) for k in ("rule", "value", "limit", "round")}


def session_view(loaded: LoadedStudy, row: ParticipantRow, facts: RoundFacts | None = None,
                 quiz_attempts_used: int = 0, detail: dict[str, Any] | None = None) -> dict[str, Any]:
    """``detail``: why a participant screened out for not taking part was (:func:`screen_out_detail`)."""
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
        "test_run": row.test_run,
        "fov_angle": _angle(study, step if step.kind == "trial" else next(iter(trial_steps), None)),
        "device": _device(row, study.device),
        "notice": "round_ended_away" if facts is not None and facts.previous_ended_away else None,
    }
    texts = study_length(study, (sum(s.trial_kind == "practice" for s in trial_steps),
                                 sum(s.trial_kind == "main" for s in trial_steps))).placeholders()
    if phase is Phase.CONSENT:
        view["consent"] = fill_placeholders(study.consent, texts)
    elif phase is Phase.INSTRUCTIONS:
        view["instructions"] = fill_placeholders(study.instructions, texts)
        view["views"] = sorted({s.view or DEFAULT_VIEW for s in trial_steps})  # which keys and picture to teach
    elif phase is Phase.QUIZ and study.quiz is not None:
        view["quiz"] = {"questions": [{"id": q.id, "text": q.text, "options": list(q.options)}
                                      for q in study.quiz.questions],
                        "attempts_used": quiz_attempts_used, "max_attempts": study.quiz.max_attempts}
    elif phase in (Phase.PRACTICE, Phase.TRIAL):
        view["trial"] = {"kind": step.trial_kind, "index": step.index, "number": step.number,
                         "total": step.total, "kind_number": (step.index or 0) + 1,
                         "kind_total": sum(1 for s in progress.plan if s.trial_kind == step.trial_kind),
                         "scored": step.trial_kind == "main",
                         "status": facts.current if facts is not None else None,
                         "view": step.view or DEFAULT_VIEW, "websocket": "/ws/play",
                         "kitchen_waits": study.timing.mode == "wait_for_participant"}
    elif phase is Phase.QUESTIONNAIRE:
        questionnaire = next(q for q in study.questionnaires if q.id == step.questionnaire)
        view["questionnaire"] = {
            "id": questionnaire.id, "title": questionnaire.title, "after_trial": step.after_trial,
            "items": [item_view(i) for i in questionnaire.items],
        }
    if phase in (Phase.DONE, Phase.SCREENED_OUT):
        view["completion"] = payment.shown_to(row, completion(loaded, row))
        if detail is not None and view["completion"].get("reason") == "low_engagement":
            view["completion"]["detail"] = detail
    return view


def item_view(item: Item) -> dict[str, Any]:
    """A questionnaire item as the page needs it (its type and how it is answered)."""
    out: dict[str, Any] = {"id": item.id, "text": item.text, "type": item.type, "required": item.required}
    if item.scale is not None:
        out["scale"] = {"min": item.scale.min, "max": item.scale.max,
                        "labels": {str(k): v for k, v in item.scale.labels.items()}}
    if item.type == "choice":
        out["options"] = list(item.options)
    if item.type == "text":
        out["min_length"], out["max_length"] = item.min_length, item.max_length
    return out


def _device(row: ParticipantRow, required: DeviceRequirements) -> dict[str, Any] | None:
    """The last device check (``None`` before the browser reported one) and the study's minimum screen."""
    if not row.device:
        return None
    problems = list(row.device.get("problems", []))
    return {"ok": not problems, "problems": problems, "min_width": required.min_width,
            "min_height": required.min_height}


def _angle(study: Study, step: Step | None) -> float:
    """The field of view the participant plays (or will first play) with: the instructions draw their cone with
    it, and the first-person camera shows it anyway; a plain number, never named as a condition."""
    return study.trial_angle(step.fov_angle if step is not None else None)
