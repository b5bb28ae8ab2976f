"""Checking a comprehension-quiz submission and what one attempt answers
(see :func:`server.flow.service.submit_quiz`)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from server.flow.answers import answer_problem
from study_config.study.quiz import Quiz


@dataclass(frozen=True)
class QuizResult:
    """One stored attempt: whether it passed, its number, how many remain, and the questions got wrong
    (id → explanation)."""

    passed: bool
    attempt: int
    attempts_left: int
    wrong: dict[str, str]

    def to_dict(self) -> dict[str, Any]:
        return {"passed": self.passed, "attempt": self.attempt, "attempts_left": self.attempts_left,
                "wrong": [{"id": qid, "explanation": text} for qid, text in self.wrong.items()]}


def quiz_problems(quiz: Quiz, answers: dict[str, Any]) -> list[dict[str, Any]]:
    """Every problem of a quiz submission (the questionnaire's 422 shape): unknown or unanswered questions,
    answers that are not an option's 0-based index."""
    ids = {q.id for q in quiz.questions}
    problems = [answer_problem(k, "unknown_item", "no such question") for k in sorted(answers) if k not in ids]
    for question in quiz.questions:
        value = answers.get(question.id)
        if value is None:
            problems.append(answer_problem(question.id, "missing", "this question needs an answer"))
        elif isinstance(value, bool) or not isinstance(value, int) or not 0 <= value < len(question.options):
            problems.append(answer_problem(question.id, "out_of_range",
                                            f"choose an option 0..{len(question.options) - 1}, got {value!r}"[:120]))
    return problems
