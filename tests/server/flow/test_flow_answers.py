"""Questionnaire answers: every problem reported, typed, located."""

from __future__ import annotations

from server.flow.answers import check_answers
from study_config.study.questionnaire import Questionnaire

Q = Questionnaire.model_validate({"id": "q", "items": [
    {"id": "a", "text": "A", "scale": {"min": 1, "max": 7}},
    {"id": "b", "text": "B", "scale": {"min": 1, "max": 7}, "required": False}]})


def types(answers):
    return [(p["loc"][-1], p["type"]) for p in check_answers(Q, answers)]


def test_valid_answers_pass():
    assert check_answers(Q, {"a": 1, "b": 7}) == []
    assert check_answers(Q, {"a": 4}) == []
    assert check_answers(Q, {"a": 4, "b": None}) == []


def test_each_problem_is_named():
    assert types({}) == [("a", "missing")]
    assert types({"a": None}) == [("a", "missing")]
    assert types({"a": 0, "b": 8}) == [("a", "out_of_range"), ("b", "out_of_range")]
    assert types({"a": "3", "b": 2.5}) == [("a", "not_integer"), ("b", "not_integer")]
    assert types({"a": True}) == [("a", "not_integer")]
    assert types({"a": 3, "zzz": 1}) == [("zzz", "unknown_item")]
    assert check_answers(Q, {})[0]["loc"] == ["body", "answers", "a"]
