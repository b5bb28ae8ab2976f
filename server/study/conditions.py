"""Experimental conditions: one robot in one kitchen (seen in one view), crossed over the study's within-subject
factors."""

from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence
from typing import Literal

from server.study.base import StudyModel
from server.study.views import DEFAULT_VIEW, ViewName

Factor = Literal["robot", "kitchen", "view"]

FACTORS: tuple[Factor, ...] = ("robot", "kitchen", "view")
"""Every factor a study may cross, in the order of the condition's fields."""


class Condition(StudyModel):
    """One cell of the design: the robot planner, the kitchen and the view a trial is played with."""

    robot: str
    """Robot planner name."""
    kitchen: str
    """Kitchen name (the layout file's stem)."""
    view: ViewName = DEFAULT_VIEW
    """How the participant sees the kitchen (``server.study.views``)."""
    view_is_factor: bool = False
    """Whether ``view`` is one of the study's factors (then it is part of the id)."""

    @property
    def id(self) -> str:
        """Stable id used in orders, the store and exports: ``robot@kitchen`` (``fov_aware@none_3``), and
        ``robot@kitchen@view`` (``fov_aware@none_3@first_person``) in a study with a view factor."""
        return condition_id(self.robot, self.kitchen, self.view if self.view_is_factor else None)


def condition_id(robot: str, kitchen: str, view: str | None = None) -> str:
    """The id of the condition pairing ``robot`` with ``kitchen`` (and ``view`` when it is a factor)."""
    return f"{robot}@{kitchen}" if view is None else f"{robot}@{kitchen}@{view}"


def cross_conditions(levels: Mapping[Factor, Sequence[str]], factors: Sequence[Factor]) -> tuple[Condition, ...]:
    """The cross product of every factor's ``levels``: the factors in ``factors`` order, the first varying
    slowest; a dimension that is not a factor has one level and comes last."""
    order = [*factors, *(f for f in FACTORS if f not in factors)]
    view_is_factor = "view" in factors
    return tuple(
        Condition.model_validate({**dict(zip(order, combination)), "view_is_factor": view_is_factor})
        for combination in itertools.product(*(levels[f] for f in order))
    )
