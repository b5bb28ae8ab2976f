"""A study's own robots: an installed robot (``planner.robot_catalog``: a shipped planner or a plug-in) with some
of its settings changed.

A researcher who compares, say, the FOV-aware robot with one that explores longer walks writes::

    robots: [fov_aware, fov_aware_far, baseline]
    robot_variants:
      fov_aware_far:
        planner: fov_aware
        settings: {exploration_depth: 6}

A variant's name is a level of the robot factor like a planner's (it appears in conditions, the store and the
exports; never in the participant's browser). Its settings are fields of the robot's declared settings (for the
shipped planners :class:`planner.planner_config.PlannerConfig`; for a plug-in its own dataclass, docs/robots.md),
each checked by name and type; the robot's model of the person's view and KB delay are the trial's (``world`` and
``fov_angles``), never a variant's (docs/domain.md §5).
"""

from __future__ import annotations

import dataclasses
import math
import typing
from functools import cache
from typing import Annotated, Any

from pydantic import AfterValidator, Field, TypeAdapter, ValidationError, ValidationInfo, field_validator

from planner import robot_catalog
from study_config.study.base import Loc, RobotName, Slug, StudyModel, raise_problems

STUDY_SET = {"human_angle": "world.fov_angle or fov_angles", "human_delay": "world.kb_delay"}
"""Planner settings a variant may not change: the study sets them for every robot of a trial."""

_KINDS: dict[Any, str] = {int: "an integer", float: "a number", bool: "true or false", str: "text"}


class RobotVariant(StudyModel):
    """A robot of the study: ``planner`` with ``settings`` changed."""

    planner: RobotName
    """The installed robot it is (``fov_aware``, ``fov_aware_showing``, ``baseline``, ``no_rollout``, ``stay``, or a
    plug-in)."""
    settings: dict[str, Any] = Field(default_factory=dict)
    """Settings of that robot (for the shipped planners ``PlannerConfig`` fields, docs/domain.md §5; for a plug-in
    its declared settings, ``steakhouse robots --settings NAME``) that differ from its defaults."""

    @field_validator("settings")
    @classmethod
    def _check_settings(cls, settings: dict[str, Any], info: ValidationInfo) -> dict[str, Any]:
        name = info.data.get("planner")
        if name is None:  # the planner is invalid: that is the problem reported
            return settings
        entry = robot_catalog.entry(name)
        declared = entry.usable().settings
        problems: list[tuple[Loc, str]] = []
        checked: dict[str, Any] = {}
        for key, value in settings.items():
            value, problem = check_setting(key, value, declared, entry.shipped, name)
            if problem is not None:
                problems.append(((key,), problem))
            checked[key] = value
        raise_problems(problems, settings)
        try:
            declared(**checked)
        except (ValueError, TypeError) as exc:  # the settings dataclass's own checks
            raise_problems([((), str(exc))], settings)
        return checked


def check_setting(key: str, value: Any, declared: type, shipped: bool, robot: str) -> tuple[Any, str | None]:
    """``value`` as the setting ``key`` of ``declared`` (a robot's settings dataclass) takes it, and why it is not
    one a variant may give (``None`` when it is). An integer is a number too; nothing else is converted (``"3"`` is
    not 3, ``1`` is not true). A shipped planner's counts are 0 or more."""
    if key in STUDY_SET:
        return value, f"set by the study for every robot ({STUDY_SET[key]}), not by a robot variant"
    hints = _hints(declared)
    if key not in hints:
        known = ", ".join(k for k in hints if k not in STUDY_SET) or "none"
        return value, f"unknown setting {key!r} of robot {robot!r}; its settings: {known}"
    kind = hints[key]
    number = kind is float and isinstance(value, int) and not isinstance(value, bool)
    try:
        checked = _adapter(kind).validate_python(float(value) if number else value, strict=True)
    except ValidationError as exc:
        wanted = _KINDS.get(kind)
        return value, (f"must be {wanted}, not {value!r}" if wanted is not None
                       else f"{exc.errors()[0]['msg']}, not {value!r}")
    if isinstance(checked, float) and not math.isfinite(checked):
        return value, "must be a finite number"
    if shipped and kind is int and checked < 0:
        return value, "must be 0 or more"
    return checked, None


@cache
def _hints(declared: type) -> dict[str, Any]:
    """Each field of a settings dataclass and its type (annotations resolved, e.g. ``Annotated`` with bounds)."""
    hints = typing.get_type_hints(declared, include_extras=True)
    return {f.name: hints[f.name] for f in dataclasses.fields(declared)}


@cache
def _adapter(kind: Any) -> TypeAdapter[Any]:
    return TypeAdapter(kind)


MAX_NAME = robot_catalog.MAX_NAME
"""The longest variant name: it is stored with every trial and is part of its condition's id."""


def _own_name(name: str) -> str:
    if robot_catalog.find(name) is not None:
        raise ValueError(f"{name!r} is an installed robot's name; give the variant its own name")
    if len(name) > MAX_NAME:
        raise ValueError(f"at most {MAX_NAME} characters (the name is stored with every trial)")
    return name


VariantName = Annotated[Slug, AfterValidator(_own_name)]
"""A robot variant's name: an id that is no installed robot's name (a level of the robot factor names one robot)."""
