"""Checking a questionnaire submission against its items: every problem is reported at once.

Each answer is an integer within the item's scale, or ``null`` / absent for an item that is not required.
Problem types: ``missing`` (a required item without an answer), ``not_integer``, ``out_of_range``,
``unknown_item``. The API answers 422 with ``{"detail": [{"loc": ["body", "answers", item], "type": ...,
"msg": ...}]}`` — the same shape as FastAPI's own validation errors.
"""

from __future__ import annotations

from typing import Any

from server.study.questionnaire import Questionnaire


def check_answers(questionnaire: Questionnaire, answers: dict[str, Any]) -> list[dict[str, Any]]:
    problems: list[dict[str, Any]] = []
    known = {item.id for item in questionnaire.items}
    for key in sorted(answers):
        if key not in known:
            problems.append(_problem(key, "unknown_item", f"{questionnaire.id!r} has no item {key!r}"))
    for item in questionnaire.items:
        value = answers.get(item.id)
        if value is None:
            if item.required:
                problems.append(_problem(item.id, "missing", "this item needs an answer"))
            continue
        if isinstance(value, bool) or not isinstance(value, int):
            problems.append(_problem(item.id, "not_integer", f"answer with an integer, got {value!r}"[:120]))
        elif not item.scale.min <= value <= item.scale.max:
            problems.append(_problem(item.id, "out_of_range",
                                     f"{value} is outside {item.scale.min}..{item.scale.max}"))
    return problems


def _problem(item: str, kind: str, message: str) -> dict[str, Any]:
    return {"loc": ["body", "answers", item], "type": kind, "msg": message}
