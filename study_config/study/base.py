"""Shared pieces of the study models: the frozen base class, ids, robot names, and located errors."""

from __future__ import annotations

import re
from collections.abc import Sequence
from typing import Annotated, Any

from pydantic import AfterValidator, BaseModel, BeforeValidator, ConfigDict, ValidationError
from pydantic_core import InitErrorDetails, PydanticCustomError

from planner import robot_catalog

STUDY_ERROR = "study"
"""Error type of every problem raised by the study's own checks (as opposed to pydantic's type checks)."""

Loc = tuple[str | int, ...]

_SLUG = re.compile(r"^[a-z0-9](?:[a-z0-9_-]*[a-z0-9])?$")


class StudyModel(BaseModel):
    """Base of every study model: immutable, and unknown keys are errors (a typo is never ignored)."""

    model_config = ConfigDict(frozen=True, extra="forbid")


def raise_problems(problems: Sequence[tuple[Loc, str]], value: Any,
                   where: Sequence[str | None] = ()) -> None:
    """Raise every ``(location, reason)`` at once, located below the field being validated.

    Pydantic merges a ``ValidationError`` raised inside a validator into the outer one, prefixing
    each location with the field's own, so one validator can report several precise problems. ``where``
    (one per problem, optional) names the place in another file a problem comes from (a kitchen layout's
    ``file:line:column``); the loader prints it after the field.
    """
    if not problems:
        return
    places = list(where) + [None] * (len(problems) - len(where))
    raise ValidationError.from_exception_data(
        "Study",
        [
            InitErrorDetails(
                type=PydanticCustomError(STUDY_ERROR, "{reason}",
                                         {"reason": reason, **({"where": place} if place else {})}),
                loc=loc,
                input=value,
            )
            for (loc, reason), place in zip(problems, places, strict=True)
        ],
    )


def duplicate_problems(values: Sequence[Any], what: str, suffix: Loc = ()) -> list[tuple[Loc, str]]:
    """One problem per value that already appeared earlier in ``values``, located at its index."""
    first: dict[Any, int] = {}
    problems: list[tuple[Loc, str]] = []
    for index, value in enumerate(values):
        if value in first:
            problems.append(((index, *suffix), f"duplicate {what} {value!r} (already at [{first[value]}])"))
        else:
            first[value] = index
    return problems


MAX_ID = 64
"""The longest id: the store keeps ids (the study's, questionnaires' and their items') in 64-character columns."""


def _check_slug(value: str) -> str:
    if not _SLUG.match(value):
        raise ValueError(
            f"{value!r} is not a valid id: use lowercase letters, digits, '-' and '_', "
            "starting and ending with a letter or digit"
        )
    if len(value) > MAX_ID:
        raise ValueError(f"an id has at most {MAX_ID} characters (it is stored with the data)")
    return value


def robot_problem(value: str, known: Sequence[str] | None = None) -> str:
    """Why ``value`` is not the name of a robot: an installed robot's (``planner.robot_catalog``), or one of
    ``known`` (those and a study's own variants). An installed robot that cannot be used says why (a plug-in that
    cannot be imported, written for another contract version …)."""
    found = robot_catalog.find(value)
    if found is not None and found.problem is not None:
        return f"robot {value!r} ({found.package} {found.version}, {found.source}) cannot be used: {found.problem}"
    names = known if known is not None else robot_catalog.usable_names()
    return f"unknown robot {value!r}; choose one of: {', '.join(names)}"


def _check_robot(value: str) -> str:
    found = robot_catalog.find(value)
    if found is None or found.problem is not None:
        raise ValueError(robot_problem(value))
    return value


Slug = Annotated[str, AfterValidator(_check_slug)]
"""An identifier used in URLs, CSV columns and the store: lowercase letters, digits, ``-`` and ``_``."""

RobotName = Annotated[str, AfterValidator(_check_robot)]
"""The name of a usable installed robot: a shipped planner (docs/domain.md §5) or a plug-in (docs/robots.md)."""


def _check_not_empty(value: Any) -> Any:
    if isinstance(value, (list, tuple)) and not value:
        raise ValueError("needs at least one entry")
    return value


NotEmpty = BeforeValidator(_check_not_empty)
"""Annotation metadata for a list field that must have at least one entry."""
