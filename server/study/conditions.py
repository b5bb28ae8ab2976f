"""Experimental conditions: one robot in one kitchen, crossed over the study's within-subject factors."""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from typing import Literal

from server.study.base import StudyModel

Factor = Literal["robot", "kitchen"]


class Condition(StudyModel):
    """One cell of the design: the robot planner and the kitchen a trial is played with."""

    robot: str
    """Robot planner name."""
    kitchen: str
    """Kitchen name (the layout file's stem)."""

    @property
    def id(self) -> str:
        """Stable id used in orders, the store and exports: ``robot@kitchen`` (``fov_aware@none_3``)."""
        return condition_id(self.robot, self.kitchen)


def condition_id(robot: str, kitchen: str) -> str:
    """The id of the condition pairing ``robot`` with ``kitchen``."""
    return f"{robot}@{kitchen}"


def cross_conditions(
    robots: Sequence[str], kitchens: Sequence[str], factors: Sequence[Factor]
) -> tuple[Condition, ...]:
    """The cross product of robots and kitchens; the first factor varies slowest."""
    if tuple(factors[:1]) == ("kitchen",):
        pairs = [(r, k) for k, r in itertools.product(kitchens, robots)]
    else:
        pairs = list(itertools.product(robots, kitchens))
    return tuple(Condition(robot=r, kitchen=k) for r, k in pairs)
