"""Experimental conditions: one robot in one kitchen (seen in one view, at one field-of-view angle). The study's
factors cross into them in ``study_config/study/design.py``."""

from __future__ import annotations

from typing import Literal

from planner.perception import FOV_ANGLE
from study_config.study.base import StudyModel
from study_config.study.fov_angles import angle_level
from study_config.study.views import DEFAULT_VIEW, ViewName

Factor = Literal["robot", "kitchen", "view", "fov_angle"]

FACTORS: tuple[Factor, ...] = ("robot", "kitchen", "view", "fov_angle")
"""Every factor a study may cross, in the order of the condition's fields."""


class Condition(StudyModel):
    """One cell of the design: the robot planner, the kitchen, the view and the field of view a trial is played
    with."""

    robot: str
    """Robot planner name."""
    kitchen: str
    """Kitchen name (the layout file's stem)."""
    view: ViewName = DEFAULT_VIEW
    """How the participant sees the kitchen (``study_config.study.views``)."""
    fov_angle: float = FOV_ANGLE
    """The participant's field of view in degrees (``study_config.study.fov_angles``)."""
    view_is_factor: bool = False
    """Whether ``view`` is one of the study's factors (then it is part of the id)."""
    fov_angle_is_factor: bool = False
    """Whether ``fov_angle`` is one of the study's factors (then it is part of the id)."""

    @property
    def id(self) -> str:
        """Stable id used in orders, the store and exports: ``robot@kitchen`` (``fov_aware@none_3``), then
        ``@view`` in a study with a view factor (``fov_aware@none_3@first_person``) and ``@angle`` in one with a
        field-of-view factor (``fov_aware@none_3@150``)."""
        return condition_id(self.robot, self.kitchen, self.view if self.view_is_factor else None,
                            self.fov_angle if self.fov_angle_is_factor else None)


def condition_id(robot: str, kitchen: str, view: str | None = None, fov_angle: float | None = None) -> str:
    """The id of the condition pairing ``robot`` with ``kitchen`` (and ``view``, ``fov_angle`` when factors)."""
    parts = [robot, kitchen, *([view] if view is not None else []),
             *([angle_level(fov_angle)] if fov_angle is not None else [])]
    return "@".join(parts)
