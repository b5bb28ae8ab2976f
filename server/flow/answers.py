"""Checking a questionnaire submission against its items: every problem is reported at once.

Answers by item type: a rating is an integer within the item's scale; a choice is the 0-based index of an
option; a text is a string (spaces at either end are trimmed; within ``min_length`` .. ``max_length``
characters). ``null``, absent, or text that is only spaces: not answered, allowed for items that are not
required. Problem types: ``missing`` (a required item without an answer), ``not_integer``, ``out_of_range``,
``not_text``, ``too_short``, ``too_long``, ``unknown_item``. The API answers 422 with ``{"detail": [{"loc":
["body", "answers", item], "type": ..., "msg": ...}]}`` — the same shape as FastAPI's own validation errors.
"""

from __future__ import annotations

from typing import Any

from study_config.study.questionnaire import Item, Questionnaire


def check_answers(questionnaire: Questionnaire, answers: dict[str, Any]) -> list[dict[str, Any]]:
    problems: list[dict[str, Any]] = []
    known = {item.id for item in questionnaire.items}
    for key in sorted(answers):
        if key not in known:
            problems.append(answer_problem(key, "unknown_item", f"{questionnaire.id!r} has no item {key!r}"))
    for item in questionnaire.items:
        value = _given(answers.get(item.id))
        if value is None:
            if item.required:
                problems.append(answer_problem(item.id, "missing", "this item needs an answer"))
            continue
        problem = _check(item, value)
        if problem is not None:
            problems.append(answer_problem(item.id, *problem))
    return problems


def stored_answer(item: Item, raw: Any) -> tuple[int | None, str | None]:
    """The ``(value, text)`` stored for a checked answer: a rating's value; a choice's index and its option's
    text; a free text (trimmed). ``(None, None)`` when the item was left unanswered."""
    given = _given(raw)
    if given is None:
        return None, None
    if item.type == "text":
        return None, str(given)
    if item.type == "choice":
        return int(given), item.options[int(given)]
    return int(given), None


def _given(raw: Any) -> Any:
    if isinstance(raw, str):
        raw = raw.strip()
        return raw or None
    return raw


def _check(item: Item, value: Any) -> tuple[str, str] | None:
    if item.type == "text":
        if not isinstance(value, str):
            return "not_text", f"answer with text, got {value!r}"[:120]
        if item.min_length is not None and len(value) < item.min_length:
            return "too_short", f"write at least {item.min_length} characters (this has {len(value)})"
        if len(value) > item.max_length:
            return "too_long", f"write at most {item.max_length} characters (this has {len(value)})"
        return None
    if isinstance(value, bool) or not isinstance(value, int):
        return "not_integer", f"answer with an integer, got {value!r}"[:120]
    if item.type == "choice":
        if not 0 <= value < len(item.options):
            return "out_of_range", f"{value} is not an option: choose 0..{len(item.options) - 1}"
        return None
    assert item.scale is not None
    if not item.scale.min <= value <= item.scale.max:
        return "out_of_range", f"{value} is outside {item.scale.min}..{item.scale.max}"
    return None


def answer_problem(item: str, kind: str, message: str) -> dict[str, Any]:
    return {"loc": ["body", "answers", item], "type": kind, "msg": message}
