"""Questionnaires shown to participants between trials: rating-scale items (e.g. 7-point Likert)."""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field, field_validator, model_validator

from server.study.base import Loc, NotEmpty, Slug, StudyModel, duplicate_problems, raise_problems


class Scale(StudyModel):
    """An integer rating scale from ``min`` to ``max`` inclusive, with optional anchor labels."""

    min: int
    """Lowest answer (e.g. 1)."""
    max: int
    """Highest answer (e.g. 7); must be greater than ``min``."""
    labels: dict[int, str] = Field(default_factory=dict)
    """Text shown under some points of the scale, keyed by value (e.g. ``{1: Strongly disagree}``)."""

    @model_validator(mode="after")
    def _check_range(self) -> Scale:
        problems: list[tuple[Loc, str]] = []
        if self.max <= self.min:
            problems.append((("max",), f"max ({self.max}) must be greater than min ({self.min})"))
        else:
            for value in self.labels:
                if not self.min <= value <= self.max:
                    reason = f"label for {value} is outside {self.min}..{self.max}"
                    problems.append((("labels", value), reason))
        raise_problems(problems, self)
        return self


class Item(StudyModel):
    """One question: a statement rated on a scale."""

    id: Slug
    """Stable id of the item, unique in its questionnaire; names the answer's column in exports."""
    text: str = Field(min_length=1)
    """The statement or question shown to the participant (plain text)."""
    scale: Scale
    """How the participant answers."""
    required: bool = True
    """Whether the participant must answer before continuing."""


class Questionnaire(StudyModel):
    """A page of items, shown after every trial or once at the end of the study."""

    id: Slug
    """Stable id, unique in the study; prefixes the item columns in exports (``post_trial.trust``)."""
    title: str = ""
    """Heading shown above the items (optional)."""
    when: Literal["after_each_trial", "end_of_study"] = "after_each_trial"
    """``after_each_trial``: after every experimental trial (not after practice);
    ``end_of_study``: once, after the last trial."""
    items: Annotated[tuple[Item, ...], NotEmpty]
    """The questions, in the order shown."""

    @field_validator("items")
    @classmethod
    def _unique_items(cls, items: tuple[Item, ...]) -> tuple[Item, ...]:
        raise_problems(duplicate_problems([item.id for item in items], "item id", ("id",)), items)
        return items
