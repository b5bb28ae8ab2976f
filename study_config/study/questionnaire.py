"""Questionnaires shown to participants between trials.

Three kinds of item (``type``):

- ``rating`` (the default): an integer on a scale (e.g. a 7-point Likert item); ``reverse: true`` marks an
  item worded the other way round, reversed as ``min + max − value`` when it is combined with others.
- ``text``: free text, with optional ``min_length`` / ``max_length`` (characters, after trimming spaces).
- ``choice``: one of a list of ``options``; stored as the option's 0-based index and its text.

``scales`` group rating items of one questionnaire into named scales for the analysis: a scale's score is
the mean of its items after reversal (docs/analysis.md).
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field, field_validator, model_validator

from study_config.study.base import Loc, NotEmpty, Slug, StudyModel, duplicate_problems, raise_problems

TEXT_LIMIT = 10_000
"""The longest free-text answer any study may allow (characters)."""

ItemType = Literal["rating", "text", "choice"]


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


_ONLY_FOR: dict[str, ItemType] = {"scale": "rating", "reverse": "rating", "options": "choice",
                                  "min_length": "text", "max_length": "text"}


class Item(StudyModel):
    """One question: a statement rated on a scale, a free-text question, or a single choice."""

    id: Slug
    """Stable id of the item, unique in its questionnaire; names the answer's column in exports."""
    text: str = Field(min_length=1)
    """The statement or question shown to the participant (plain text)."""
    type: ItemType = "rating"
    """``rating`` (default), ``text`` or ``choice``."""
    required: bool = True
    """Whether the participant must answer before continuing."""
    scale: Scale | None = None
    """Rating items: how the participant answers (required for ratings)."""
    reverse: bool = False
    """Rating items: worded the other way round (reversed as ``min + max − value`` in scales)."""
    options: tuple[Annotated[str, Field(min_length=1)], ...] = ()
    """Choice items: the options, in the order shown (at least two)."""
    min_length: int | None = Field(default=None, ge=1)
    """Text items: fewest characters of an answer (optional)."""
    max_length: int = Field(default=2000, ge=1, le=TEXT_LIMIT)
    """Text items: most characters of an answer (default 2000, at most 10000)."""

    @model_validator(mode="after")
    def _fields_fit_the_type(self) -> Item:
        problems: list[tuple[Loc, str]] = []
        for name, kind in _ONLY_FOR.items():
            written = name in self.model_fields_set and getattr(self, name) != Item.model_fields[name].default
            if kind != self.type and written:
                problems.append(((name,), f"only used by {kind} items, not by a {self.type} item"))
        if self.type == "rating" and self.scale is None:
            problems.append((("scale",), "required field is missing (a rating item needs a scale {min, max, labels})"))
        if self.type == "choice":
            if len(self.options) < 2:
                problems.append((("options",), "a choice item needs at least two options"))
            problems += [(("options", *loc), reason) for loc, reason in duplicate_problems(self.options, "option")]
        if self.type == "text" and self.min_length is not None and self.min_length > self.max_length:
            problems.append((("min_length",), f"min_length ({self.min_length}) is above max_length "
                                              f"({self.max_length})"))
        raise_problems(problems, self)
        return self


class NamedScale(StudyModel):
    """Rating items of one questionnaire combined into one score for the analysis (their mean, reversed items
    first reversed)."""

    id: Slug
    """Stable id, unique in its questionnaire; exported as ``<questionnaire id>.<scale id>``."""
    title: str = ""
    """What the scale measures, for the data dictionary and the report (e.g. *Perceived fluency*)."""
    items: Annotated[tuple[str, ...], NotEmpty]
    """Ids of rating items of this questionnaire, all on the same scale."""


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
    scales: tuple[NamedScale, ...] = ()
    """Named scales made of this questionnaire's rating items (optional)."""

    @field_validator("items")
    @classmethod
    def _unique_items(cls, items: tuple[Item, ...]) -> tuple[Item, ...]:
        raise_problems(duplicate_problems([item.id for item in items], "item id", ("id",)), items)
        return items

    @model_validator(mode="after")
    def _scales_name_rating_items(self) -> Questionnaire:
        items = {item.id: item for item in self.items}
        problems: list[tuple[Loc, str]] = [
            (("scales", *loc), reason) for loc, reason in duplicate_problems([s.id for s in self.scales],
                                                                              "scale id", ("id",))]
        for s_index, scale in enumerate(self.scales):
            if scale.id in items:
                problems.append((("scales", s_index, "id"), f"{scale.id!r} is also an item id; exports name both "
                                                             f"<questionnaire>.<id>, so give the scale another id"))
            ranges = set()
            for i_index, item_id in enumerate(scale.items):
                where: Loc = ("scales", s_index, "items", i_index)
                item = items.get(item_id)
                if item is None:
                    problems.append((where, f"no item {item_id!r} in this questionnaire; items are: "
                                            f"{', '.join(items)}"))
                elif item.type != "rating" or item.scale is None:
                    problems.append((where, f"item {item_id!r} is a {item.type} item; scales combine rating items"))
                else:
                    ranges.add((item.scale.min, item.scale.max))
            if len(ranges) > 1:
                shown = ", ".join(f"{lo}..{hi}" for lo, hi in sorted(ranges))
                problems.append((("scales", s_index, "items"), f"items of one scale must share one rating range "
                                                               f"(found {shown})"))
            problems += [(("scales", s_index, "items", *loc), reason)
                         for loc, reason in duplicate_problems(scale.items, "item")]
        raise_problems(problems, self)
        return self

    def item(self, item_id: str) -> Item | None:
        """The item called ``item_id``, if any."""
        return next((item for item in self.items if item.id == item_id), None)
