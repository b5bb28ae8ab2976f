"""The study: what an experimenter writes in ``study_config/<id>.yaml``, parsed into frozen models.

A study crosses robot planners with kitchens (the within-subject factors) into conditions, orders them
per participant by a counterbalancing scheme, and fixes every number that shapes a trial. The resolved
model's :meth:`Study.config_hash` is stored with every trial, so two trials with the same hash ran under
the same settings (principle 6 of STYLE.md).
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Sequence
from typing import Annotated, Any

from pydantic import Field, ValidationInfo, field_validator

from planner.perception import FOV_ANGLE
from planner.robot_catalog import usable_names
from study_config.study.base import (
    Loc,
    NotEmpty,
    Slug,
    StudyModel,
    duplicate_problems,
    raise_problems,
    robot_problem,
)
from study_config.study.conditions import Condition, Factor
from study_config.study.counterbalance import MAX_FULL_CONDITIONS, condition_orders
from study_config.study.design import Design, view_levels
from study_config.study.device import DeviceRequirements
from study_config.study.fov_angles import angle_level
from study_config.study.groups import between_problems, scheme_problems
from study_config.study.kitchens import Kitchen, KitchenEntry, base_dir_of, entry_name, resolve_kitchens
from study_config.study.questionnaire import Questionnaire
from study_config.study.quiz import Quiz
from study_config.study.robots import RobotVariant, VariantName
from study_config.study.sections import Assignment, Counterbalancing, Practice, Reconnect, Recruiting, Timing, World
from study_config.study.texts import DEFAULT_CONSENT, DEFAULT_INSTRUCTIONS
from study_config.study.validity import Validity
from study_config.study.views import ViewName

_FACTOR_LEVELS = {"robot": "robots", "kitchen": "kitchens", "view": "views", "fov_angle": "fov_angles"}


class Study(StudyModel):
    """A complete study definition; see ``study_config/paper_study.yaml`` for a commented example."""

    id: Slug
    """Stable id; appears in participant links and the store. Changing it starts a new study."""
    title: str = Field(min_length=1)
    """Human-readable name shown to experimenters."""
    description: str = ""
    """What the study is about, for experimenters (not shown to participants)."""
    kitchens: Annotated[tuple[KitchenEntry, ...], NotEmpty]
    """Levels of the kitchen factor: shipped kitchen names or layout paths relative to the study file."""
    robot_variants: dict[VariantName, RobotVariant] = Field(default_factory=dict)
    """The study's own robots, by name: a planner with some of its settings changed, e.g. ``fov_aware_far:
    {planner: fov_aware, settings: {exploration_depth: 6}}`` (``study_config/study/robots.py``)."""
    robots: Annotated[tuple[Slug, ...], NotEmpty]
    """Levels of the robot factor: installed robots (the shipped ``fov_aware``, ``fov_aware_showing``, ``baseline``,
    ``no_rollout``, ``stay``, and plug-ins: ``steakhouse robots`` lists them, docs/robots.md) or the names of
    ``robot_variants``."""
    view: ViewName | None = None
    """How participants see the kitchen in every trial: ``top_down`` (the default) or ``first_person``
    (``study_config.study.views``). Shorthand for ``views`` with one entry; write one of the two."""
    views: Annotated[tuple[ViewName, ...], NotEmpty] | None = None
    """Levels of the view factor, e.g. ``[top_down, first_person]`` with ``view`` in ``factors``. The stored
    study always has ``views`` (from ``view`` when only that was written)."""
    fov_angles: Annotated[tuple[Annotated[float, Field(gt=0, le=360)], ...], NotEmpty] | None = None
    """Levels of the field-of-view factor in degrees, e.g. ``[90, 120, 150]`` with ``fov_angle`` in ``between``
    (or in ``factors``): each trial masks the participant's view and models the person at its own angle
    (``study_config.study.fov_angles``). Without it every trial has ``world.fov_angle``; write one of the two."""
    between: tuple[Factor, ...] = ()
    """Factors between participants (``robot``, ``kitchen``, ``view``, ``fov_angle``), e.g. ``[view]`` with
    ``views: [top_down, first_person]``: each participant plays one level (one group per combination of levels),
    groups are filled in balance, and the within ``factors`` are counterbalanced inside each group
    (``study_config/study/groups.py``)."""
    factors: Annotated[tuple[Factor, ...], NotEmpty] = Field(default=("robot", "kitchen"), validate_default=True)
    """Within-subject factors (``robot``, ``kitchen``, ``view``, ``fov_angle``), crossed into the conditions; the
    first varies slowest in the condition list. A dimension left out must have a single level (e.g. one kitchen with
    ``factors: [robot]``)."""
    counterbalancing: Counterbalancing = Counterbalancing()
    """How each participant's condition order is chosen."""
    practice: tuple[Practice, ...] = ()
    """Practice trials before the conditions, in this order."""
    timing: Timing = Timing()
    """Tick rate or wait-for-participant mode."""
    world: World = World()
    """Field of view, knowledge-base delay, orders, horizon and the kitchen's timings."""
    questionnaires: tuple[Questionnaire, ...] = ()
    """Questionnaires, each shown after every trial or at the end of the study."""
    consent: str = DEFAULT_CONSENT
    """Consent page (Markdown). Declining ends the session with the screen-out code."""
    instructions: str = DEFAULT_INSTRUCTIONS
    """Instructions page shown before practice (Markdown)."""
    quiz: Quiz | None = None
    """Comprehension quiz after the instructions, to be answered correctly before the practice (optional)."""
    device: DeviceRequirements = DeviceRequirements()
    """The smallest screen (and whether touch-only devices may take part), checked on landing."""
    recruiting: Recruiting = Recruiting()
    """Recruiting-platform parameters, completion and screen-out codes and redirects."""
    reconnect: Reconnect = Reconnect()
    """What a dropped connection does to the running trial."""
    assignment: Assignment = Assignment()
    """How in-progress participants count when balancing condition orders."""
    validity: Validity = Validity()
    """When a trial is invalid (too many missed robot decisions); invalid trials are flagged and excluded."""
    test_run: bool = False
    """Mark every participant as a test run: not counted for assignment, excluded from exports by default."""
    notes: str = ""
    """Free text for experimenters (admin pages only)."""

    @field_validator("kitchens", mode="before")
    @classmethod
    def _resolve_kitchens(cls, kitchens: Any, info: ValidationInfo) -> Any:
        """Every entry resolved and its grid checked, and duplicates found, all reported together."""
        if not isinstance(kitchens, (list, tuple)):
            return kitchens
        _remember_levels(info, "kitchens", [entry_name(k) for k in kitchens])
        resolved, problems = resolve_kitchens(kitchens, base_dir_of(info))
        raise_problems([(loc, reason) for loc, reason, _ in problems], kitchens, [w for _, _, w in problems])
        return resolved

    @field_validator("robot_variants", mode="before")
    @classmethod
    def _remember_variants(cls, variants: Any, info: ValidationInfo) -> Any:
        if isinstance(variants, dict):
            _remember_levels(info, "robot_variants", [str(name) for name in variants])
        return variants

    @field_validator("robots", mode="before")
    @classmethod
    def _check_robots(cls, robots: Any, info: ValidationInfo) -> Any:
        """Unknown robots and duplicates, reported together (one never hides the other)."""
        if not isinstance(robots, (list, tuple)) or not all(isinstance(r, str) for r in robots):
            return robots
        _remember_levels(info, "robots", list(robots))
        known = tuple(dict.fromkeys((*usable_names(), *(_levels(info, "robot_variants") or ()))))
        problems = [((i,), robot_problem(r, known)) for i, r in enumerate(robots) if r not in known]
        raise_problems(sorted(problems + duplicate_problems(robots, "robot")), robots)
        return robots

    @field_validator("views")
    @classmethod
    def _check_views(cls, views: tuple[ViewName, ...] | None, info: ValidationInfo) -> tuple[ViewName, ...] | None:
        problems: list[tuple[Loc, str]] = []
        if views is not None:
            problems += duplicate_problems(views, "view")
            if info.data.get("view") is not None:
                problems.append(((), "write either view (one view for every trial) or views (the levels of "
                                     "the view factor), not both"))
        raise_problems(problems, views)
        return views

    @field_validator("fov_angles", mode="before")
    @classmethod
    def _remember_fov_angles(cls, angles: Any, info: ValidationInfo) -> Any:
        if isinstance(angles, (list, tuple)):
            _remember_levels(info, "fov_angles", list(angles))
        return angles

    @field_validator("fov_angles")
    @classmethod
    def _check_fov_angles(cls, angles: tuple[float, ...] | None) -> tuple[float, ...] | None:
        if angles is not None:
            raise_problems(duplicate_problems([angle_level(a) for a in angles], "field-of-view angle"), angles)
        return angles

    @field_validator("factors")
    @classmethod
    def _check_factors(cls, factors: tuple[Factor, ...], info: ValidationInfo) -> tuple[Factor, ...]:
        between = tuple(info.data.get("between") or ())
        problems = duplicate_problems(factors, "factor") + between_problems(factors, between)
        for factor, field in _FACTOR_LEVELS.items():
            levels = _factor_levels(info, factor, field)
            if factor in between and levels is not None and len(levels) < 2:
                problems.append(((), f"between factor {factor!r} needs at least two {field}"))
            if factor not in factors and factor not in between and levels is not None and len(levels) != 1:
                problems.append(
                    ((), f"{field} has {len(levels)} entries but {factor!r} is not a factor; "
                         f"add it to factors or keep one entry")
                )
        raise_problems(problems, factors)
        return factors

    @field_validator("counterbalancing")
    @classmethod
    def _check_counterbalancing(cls, value: Counterbalancing, info: ValidationInfo) -> Counterbalancing:
        data = {**info.data, **{field: _levels(info, field) for field in ("kitchens", "robots")}}
        if not all(data.get(field) is not None for field in ("kitchens", "robots", "factors")) or not all(
                field in data for field in ("view", "views", "fov_angles")):
            return value
        design = Design.from_config(data)
        ids = [c.id for c in design.conditions]
        problems: list[tuple[Loc, str]] = list(scheme_problems(value.scheme, tuple(data.get("between") or ())))
        per_group = len(ids) // len(design.groups())
        if value.scheme == "full" and per_group > MAX_FULL_CONDITIONS:
            problems.append(
                (("scheme",), f"full counterbalancing of {per_group} conditions gives too many orders; "
                              "use latin_square")
            )
        if value.scheme == "fixed" and value.order is not None:
            in_order = [
                ((i,), f"unknown condition {cid!r}; conditions are: {', '.join(ids)}")
                for i, cid in enumerate(value.order)
                if cid not in ids
            ] + duplicate_problems(value.order, "condition")
            problems += [(("order", *loc), reason) for loc, reason in in_order]
            missing = [cid for cid in ids if cid not in value.order]
            if missing:
                problems.append((("order",), f"missing conditions: {', '.join(missing)}"))
        raise_problems(problems, value)
        return value

    @field_validator("world")
    @classmethod
    def _one_fov_angle_field(cls, world: World, info: ValidationInfo) -> World:
        if info.data.get("fov_angles") is not None and "fov_angle" in world.model_fields_set:
            raise_problems([(("fov_angle",), "write either world.fov_angle (one field of view for every trial) or "
                                             "fov_angles (the levels of the fov_angle factor), not both")], world)
        return world

    @field_validator("questionnaires")
    @classmethod
    def _unique_questionnaires(cls, value: tuple[Questionnaire, ...]) -> tuple[Questionnaire, ...]:
        raise_problems(duplicate_problems([q.id for q in value], "questionnaire id", ("id",)), value)
        return value

    @property
    def design(self) -> Design:
        """The study's factors and their levels, and its questionnaires (``study_config/study/design.py``, the one
        definition of how they cross into conditions)."""
        return Design.from_config({**self._factor_fields(), "questionnaires": self.questionnaires})

    @property
    def _crossing(self) -> Design:
        """:attr:`design` without the questionnaires: all the conditions, orders and groups need."""
        return Design.from_config(self._factor_fields())

    def _factor_fields(self) -> dict[str, Any]:
        return {"robots": self.robots, "kitchens": self.kitchens, "view": self.view, "views": self.views,
                "fov_angles": self.fov_angles, "world": self.world, "factors": self.factors, "between": self.between}

    @property
    def view_levels(self) -> tuple[ViewName, ...]:
        """The views trials are played in: ``views``, else ``(view,)``, else the default (top-down)."""
        return self._crossing.views

    @property
    def fov_angle_levels(self) -> tuple[float, ...]:
        """The fields of view trials are played with: ``fov_angles``, else ``(world.fov_angle,)``."""
        return self._crossing.fov_angles

    @property
    def conditions(self) -> tuple[Condition, ...]:
        """Every robot × kitchen (× view × fov_angle) condition, in study order (first factor slowest)."""
        return self._crossing.conditions

    def condition_orders(self) -> list[tuple[str, ...]]:
        """The condition orders participants are assigned to (lists of condition ids); with between factors,
        each group's orders in turn (see :meth:`order_groups`)."""
        scheme = self.counterbalancing
        return [order for group in self._groups() for order in condition_orders(group, scheme.scheme, scheme.order)]

    def order_groups(self) -> list[int]:
        """The between-participants group of each order of :meth:`condition_orders` (all 0 without one)."""
        scheme = self.counterbalancing
        return [g for g, group in enumerate(self._groups())
                for _ in condition_orders(group, scheme.scheme, scheme.order)]

    def _groups(self) -> list[list[str]]:
        return self._crossing.groups()

    def practice_view(self, practice: Practice, order: Sequence[str]) -> ViewName:
        """The view of a practice round of a participant assigned ``order`` (condition ids): its own ``view``;
        else their group's view when ``view`` is between participants (they practise in the view they will play);
        else the study's first view level."""
        if practice.view is not None:
            return practice.view
        if "view" in self.between and order:
            return self._condition(order[0]).view
        return self.view_levels[0]

    def practice_angle(self, order: Sequence[str]) -> float:
        """The field of view of the practice rounds of a participant assigned ``order`` (condition ids): their
        group's angle when ``fov_angle`` is between participants (they practise with the view they will play),
        else the first angle level."""
        if "fov_angle" in self.between and order:
            return self._condition(order[0]).fov_angle
        return self.fov_angle_levels[0]

    def _condition(self, condition_id: str) -> Condition:
        return next(c for c in self.conditions if c.id == condition_id)

    def trial_angle(self, stored: float | None) -> float:
        """The field of view of a stored trial: its own ``fov_angle``, else (stored before trials recorded it,
        and not known from the store's copy of the study) the study's ``world.fov_angle``."""
        return stored if stored is not None else self.world.fov_angle

    def planner(self, robot: str) -> str:
        """The installed robot that plays the robot called ``robot`` (a level of the robot factor or a practice
        robot): a variant's ``planner``, else the robot itself."""
        variant = self.robot_variants.get(robot)
        return variant.planner if variant is not None else robot

    def robot_settings(self, robot: str) -> dict[str, Any]:
        """The settings the robot called ``robot`` changes from its planner's defaults (its variant's, checked)."""
        variant = self.robot_variants.get(robot)
        return dict(variant.settings) if variant is not None else {}

    def kitchen(self, name: str) -> Kitchen:
        """The kitchen called ``name`` among the study's and the practice kitchens."""
        for kitchen in (*self.kitchens, *(p.kitchen for p in self.practice)):
            if kitchen.name == name:
                return kitchen
        raise KeyError(name)

    def canonical_json(self) -> str:
        """The resolved study as canonical JSON (sorted keys, no spaces), without machine paths; ``views``
        always lists the view levels (``view`` is folded into it)."""
        data = self.model_dump(
            mode="json",
            exclude={"view": True, "kitchens": {"__all__": {"path"}},
                     "practice": {"__all__": {"kitchen": {"path"}}}},
        )
        data["views"] = list(self.view_levels)
        for field in ("between", "fov_angles", "robot_variants"):
            if not data[field]:
                del data[field]  # studies without these fields keep the hash they had before the fields existed
        return json.dumps(data, sort_keys=True, separators=(",", ":"), ensure_ascii=False)

    def config_hash(self) -> str:
        """SHA-256 (hex) of :meth:`canonical_json`; stored with every trial."""
        return hashlib.sha256(self.canonical_json().encode("utf-8")).hexdigest()


def _factor_levels(info: ValidationInfo, factor: str, field: str) -> Any:
    """The levels of ``factor`` for the checks of ``factors``: a view or a field of view not given as levels is
    one level (the study's ``view`` or ``world.fov_angle``)."""
    if factor == "view":
        return view_levels(info.data)
    if factor == "fov_angle":
        return _levels(info, field) or (FOV_ANGLE,)
    return _levels(info, field)


def _remember_levels(info: ValidationInfo, field: str, names: list[str | None]) -> None:
    """Keep a factor's levels as written (names) in the validation context, so the checks of later fields
    (factors, counterbalancing) still run when an entry of this field is invalid: one bad entry must not hide
    another problem of the file."""
    if isinstance(info.context, dict) and all(name is not None for name in names):
        info.context.setdefault("levels_as_written", {})[field] = tuple(names)


def _levels(info: ValidationInfo, field: str) -> Any:
    """The validated levels of ``field``, else (when it failed) its levels as written, else ``None``."""
    if info.data.get(field) is not None:
        return info.data[field]
    context = info.context if isinstance(info.context, dict) else {}
    return context.get("levels_as_written", {}).get(field)
