"""A participant's questionnaire answers for the admin: one entry per questionnaire step they submitted, in
the order they answered, each item with its text, type and scale from the study (when the study still has it)
and the stored value and text (``None`` for an optional item left out; ``text`` is a free-text answer or the
chosen option of a choice item)."""

from __future__ import annotations

from itertools import groupby
from typing import Any

from sqlalchemy import select
from sqlalchemy.orm import Session

from store.tables import AnswerRow, ParticipantRow
from study_config.catalog import LoadedStudy


def participant_answers(session: Session, row: ParticipantRow, loaded: LoadedStudy | None) -> dict[str, Any]:
    answers = session.scalars(select(AnswerRow).where(AnswerRow.participant_id == row.id)
                              .order_by(AnswerRow.step, AnswerRow.id)).all()
    questionnaires = {q.id: q for q in loaded.study.questionnaires} if loaded else {}
    out = []
    for (step, questionnaire_id), group in groupby(answers, key=lambda a: (a.step, a.questionnaire_id)):
        stored = list(group)
        known = questionnaires.get(questionnaire_id)
        texts = {i.id: i for i in known.items} if known else {}
        items = []
        for answer in stored:
            item = texts.get(answer.item_id)
            scale = item.scale if item else None
            items.append({"id": answer.item_id, "value": answer.value, "answer_text": answer.text,
                          "text": item.text if item else None, "type": item.type if item else None,
                          "scale": {"min": scale.min, "max": scale.max} if scale else None})
        out.append({"questionnaire_id": questionnaire_id, "title": known.title if known else None, "step": step,
                    "after_trial": stored[0].after_trial, "trial_id": stored[0].trial_id,
                    "answered_at": stored[0].created_at.isoformat(), "items": items})
    return {"participant_id": row.public_id, "study_id": row.study_id, "questionnaires": out}
