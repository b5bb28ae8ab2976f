"""The comprehension quiz shown after the instructions: multiple-choice questions that must all be answered
correctly before the practice starts.

A wrong answer shows its question's explanation and the participant tries again; every attempt is stored.
After ``max_attempts`` failed attempts the participant is screened out (the study's screen-out code).
"""

from __future__ import annotations

from typing import Annotated

from pydantic import Field, field_validator, model_validator

from study_config.study.base import Loc, NotEmpty, Slug, StudyModel, duplicate_problems, raise_problems


class QuizQuestion(StudyModel):
    """One multiple-choice question with exactly one correct option."""

    id: Slug
    """Stable id, unique in the quiz; names the answer in the stored attempts."""
    text: str = Field(min_length=1)
    """The question."""
    options: Annotated[tuple[Annotated[str, Field(min_length=1)], ...], NotEmpty]
    """The options, in the order shown (at least two)."""
    answer: int = Field(ge=1)
    """The number of the correct option, counting from 1."""
    explanation: str = Field(min_length=1)
    """Shown when the question was answered wrongly: the rule, in a sentence or two."""

    @model_validator(mode="after")
    def _check_options(self) -> QuizQuestion:
        problems: list[tuple[Loc, str]] = []
        if len(self.options) < 2:
            problems.append((("options",), "a question needs at least two options"))
        problems += [(("options", *loc), reason) for loc, reason in duplicate_problems(self.options, "option")]
        if self.answer > len(self.options):
            problems.append((("answer",), f"there is no option {self.answer}: the question has "
                                          f"{len(self.options)} options (count from 1)"))
        raise_problems(problems, self)
        return self

    @property
    def correct(self) -> int:
        """The correct option's 0-based index (what the participant's browser sends)."""
        return self.answer - 1


class Quiz(StudyModel):
    """The comprehension check between the instructions and the practice."""

    questions: Annotated[tuple[QuizQuestion, ...], NotEmpty]
    """The questions, in the order shown."""
    max_attempts: int = Field(default=3, ge=1)
    """Failed attempts allowed; after this many the participant is screened out (default 3)."""

    @field_validator("questions")
    @classmethod
    def _unique_questions(cls, questions: tuple[QuizQuestion, ...]) -> tuple[QuizQuestion, ...]:
        raise_problems(duplicate_problems([q.id for q in questions], "question id", ("id",)), questions)
        return questions

    def wrong(self, answers: dict[str, int]) -> list[QuizQuestion]:
        """The questions ``answers`` (question id → 0-based option index) got wrong, in quiz order."""
        return [q for q in self.questions if answers.get(q.id) != q.correct]
