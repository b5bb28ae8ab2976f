"""A study's own robots: a planner of ``planner.registry`` with some of its settings changed.

A researcher who compares, say, the FOV-aware robot with one that explores longer walks writes::

    robots: [fov_aware, fov_aware_far, baseline]
    robot_variants:
      fov_aware_far:
        planner: fov_aware
        settings: {exploration_depth: 6}

A variant's name is a level of the robot factor like a planner's (it appears in conditions, the store and the
exports; never in the participant's browser). Its settings are :class:`planner.planner_config.PlannerConfig`
fields, each checked by name and type; the robot's model of the person's view and KB delay are the trial's
(``world`` and ``fov_angles``), never a variant's (docs/domain.md §5).
"""

from __future__ import annotations

import dataclasses
import math
from typing import Annotated, Any

from pydantic import AfterValidator, Field, TypeAdapter, ValidationError, field_validator

from planner.planner_config import PlannerConfig
from planner.registry import PLANNER_NAMES
from study_config.study.base import Loc, RobotName, Slug, StudyModel, raise_problems

STUDY_SET = {"human_angle": "world.fov_angle or fov_angles", "human_delay": "world.kb_delay"}
"""Planner settings a variant may not change: the study sets them for every robot of a trial."""

_TYPES: dict[str, str] = {f.name: str(f.type) for f in dataclasses.fields(PlannerConfig)}
_KINDS: dict[str, tuple[Any, str]] = {"int": (int, "an integer"), "float": (float, "a number"),
                                      "bool": (bool, "true or false"), "str": (str, "text")}
_ADAPTERS = {name: TypeAdapter(_KINDS[kind][0]) for name, kind in _TYPES.items()}


class RobotVariant(StudyModel):
    """A robot of the study: ``planner`` with ``settings`` changed."""

    planner: RobotName
    """The planner it is (``fov_aware``, ``fov_aware_showing``, ``baseline``, ``no_rollout``, ``stay``)."""
    settings: dict[str, Any] = Field(default_factory=dict)
    """Planner settings (``PlannerConfig`` fields, docs/domain.md §5) that differ from the planner's defaults."""

    @field_validator("settings")
    @classmethod
    def _check_settings(cls, settings: dict[str, Any]) -> dict[str, Any]:
        problems: list[tuple[Loc, str]] = []
        checked: dict[str, Any] = {}
        for key, value in settings.items():
            value, problem = check_setting(key, value)
            if problem is not None:
                problems.append(((key,), problem))
            checked[key] = value
        raise_problems(problems, settings)
        return checked

    def config(self, base: PlannerConfig) -> PlannerConfig:
        """``base`` (the trial's model of the person) with this variant's settings."""
        return dataclasses.replace(base, **self.settings)


def check_setting(key: str, value: Any) -> tuple[Any, str | None]:
    """``value`` as the planner setting ``key`` takes it, and why it is not one a variant may change (``None``
    when it is). An integer is a number too; nothing else is converted (``"3"`` is not 3, ``1`` is not true)."""
    if key in STUDY_SET:
        return value, f"set by the study for every robot ({STUDY_SET[key]}), not by a robot variant"
    if key not in _ADAPTERS:
        known = ", ".join(k for k in _ADAPTERS if k not in STUDY_SET)
        return value, f"unknown planner setting {key!r}; known: {known}"
    kind = _TYPES[key]
    number = kind == "float" and isinstance(value, int) and not isinstance(value, bool)
    try:
        checked = _ADAPTERS[key].validate_python(float(value) if number else value, strict=True)
    except ValidationError:
        return value, f"must be {_KINDS[kind][1]}, not {value!r}"
    if kind == "float" and not math.isfinite(checked):
        return value, "must be a finite number"
    if kind == "int" and checked < 0:
        return value, "must be 0 or more"
    return checked, None


MAX_NAME = 32
"""The longest variant name: it is stored with every trial and is part of its condition's id."""


def _own_name(name: str) -> str:
    if name in PLANNER_NAMES:
        raise ValueError(f"{name!r} is a planner's name; give the variant its own name")
    if len(name) > MAX_NAME:
        raise ValueError(f"at most {MAX_NAME} characters (the name is stored with every trial)")
    return name


VariantName = Annotated[Slug, AfterValidator(_own_name)]
"""A robot variant's name: an id that is no planner's name (a level of the robot factor names one robot)."""
