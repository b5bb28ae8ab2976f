"""Every robot a study may name, and how one is built: one path for the shipped robots and the plug-ins.

The shipped robots (``planner.registry.PLANNER_NAMES``, built by :func:`planner.robots.make_robot`; their
settings are :class:`planner.planner_config.PlannerConfig`) come from a built-in table; a plug-in is a
:class:`planner.robot_api.RobotPlugin` that an installed package registers under the entry-point group
``steakhouse.robots`` (docs/robots.md). Both become a :class:`RobotEntry` (name, package, version, the plug-in),
and everything downstream (study validation, the server's robot workers, ``simulate``, the benchmarks) builds a
robot through :func:`build`. The built-in table rather than this distribution's own entry points: the shipped
robots are there whatever the state of the installed metadata (a source checkout, an editable install made
before a robot was added), and they can never be shadowed.

A plug-in that cannot be imported, is not a ``RobotPlugin``, was written for another contract version, has an
invalid name or settings, or shares its name with another robot, is listed with the reason (:attr:`RobotEntry.problem`)
and refused where it is named. Discovery imports the plug-ins' modules once per process.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field, replace
from functools import cache
from importlib import metadata
from typing import Any, Protocol

from planner.decision import Robot
from planner.layout import Layout
from planner.planner_config import PlannerConfig
from planner.registry import PLANNER_NAMES
from planner.robot_api import CONTRACT_VERSION, Person, RobotPlugin, settings_problem
from planner.rules import Rules

GROUP = "steakhouse.robots"
"""The entry-point group plug-in robots are registered under."""
DISTRIBUTION = "steakhouse-study"
"""This platform's distribution: the package of the shipped robots."""
MAX_NAME = 32
"""The longest robot name: it is stored with every trial and is part of its condition's id."""
_NAME = re.compile(r"^[a-z0-9](?:[a-z0-9_-]*[a-z0-9])?$")


@dataclass(frozen=True, slots=True)
class RobotSetup:
    """What a trial's robot is built with beside the kitchen and its numbers: the person the study shows and the
    robot's settings (name → value, checked against its declared settings by the study). Plain values, so it
    travels to a robot worker process."""

    person: Person = field(default_factory=Person)
    settings: tuple[tuple[str, Any], ...] = ()


class RobotFactory(Protocol):
    """``factory(name, kitchen, rules, setup)`` → a fresh :class:`planner.decision.Robot` for one trial
    (:func:`build`; the server's ``robot_factory`` setting names another for its tests)."""

    def __call__(self, name: str, layout: Layout, rules: Rules, setup: RobotSetup) -> Robot: ...


@dataclass(frozen=True, slots=True)
class RobotEntry:
    """One installed robot: its name, the package (distribution) and version that provide it, where it comes
    from (``module:attribute`` of its entry point, or ``planner.robots`` for a shipped one), the plug-in, and
    why it cannot be used (``None`` when it can)."""

    name: str
    package: str
    version: str
    source: str
    plugin: RobotPlugin[Any] | None = None
    problem: str | None = None
    shipped: bool = False

    def usable(self) -> RobotPlugin[Any]:
        """The plug-in; :class:`RobotUnavailable` with the reason when it cannot be used."""
        if self.plugin is None or self.problem is not None:
            raise RobotUnavailable(f"robot {self.name!r} ({self.package} {self.version}, {self.source}) cannot be "
                                   f"used: {self.problem}")
        return self.plugin


class RobotUnavailable(ValueError):
    """A robot that is not installed, or installed but unusable (the message says why)."""


def _shipped_plugin(name: str) -> RobotPlugin[PlannerConfig]:
    def make(layout: Layout, rules: Rules, person: Person, config: PlannerConfig) -> Robot:
        from planner.robots import make_robot

        return make_robot(name, layout, rules,
                          replace(config, human_angle=person.fov_angle, human_delay=person.kb_delay))

    return RobotPlugin(make=make, settings=PlannerConfig, summary="shipped (docs/domain.md §5)")


def platform_version() -> str:
    """The installed version of this platform's distribution (``unknown`` when run from a bare source tree)."""
    try:
        return metadata.version(DISTRIBUTION)
    except metadata.PackageNotFoundError:
        return "unknown"


@cache
def _shipped() -> dict[str, RobotEntry]:
    version = platform_version()
    return {name: RobotEntry(name, DISTRIBUTION, version, "planner.robots", _shipped_plugin(name), shipped=True)
            for name in PLANNER_NAMES}


@cache
def _entry_points() -> dict[str, tuple[metadata.EntryPoint, ...]]:
    """The registered entry points by robot name (the same one found twice on the path counted once)."""
    found: dict[str, dict[tuple[str, str], metadata.EntryPoint]] = {}
    for point in metadata.entry_points(group=GROUP):
        dist = point.dist.name if point.dist is not None else "?"
        found.setdefault(point.name, {})[(point.value, dist)] = point
    return {name: tuple(points.values()) for name, points in found.items()}


def _package(point: metadata.EntryPoint) -> tuple[str, str]:
    if point.dist is None:
        return "?", "?"
    return point.dist.name, point.dist.version


@cache
def _plugin_entry(name: str) -> RobotEntry | None:
    points = _entry_points().get(name)
    if not points:
        return None
    first = points[0]
    package, version = _package(first)

    def refused(problem: str) -> RobotEntry:
        return RobotEntry(name, package, version, first.value, problem=problem)

    if len(points) > 1:
        return refused("registered more than once: " + "; ".join(
            f"{' '.join(_package(p))} ({p.value})" for p in points))
    if name in PLANNER_NAMES:
        return refused("a shipped robot has this name; give the plug-in another")
    if not _NAME.match(name) or len(name) > MAX_NAME:
        return refused(f"its name must be lowercase letters, digits, '-' and '_', at most {MAX_NAME} characters")
    try:
        plugin = first.load()
    except (Exception, SystemExit) as exc:  # a plug-in that cannot be imported is reported, never fatal
        return refused(f"cannot be imported: {type(exc).__name__}: {exc}")
    if not isinstance(plugin, RobotPlugin):
        return refused(f"{first.value} is {type(plugin).__name__}, not a planner.robot_api.RobotPlugin")
    if plugin.contract != CONTRACT_VERSION:
        return refused(f"written for robot contract {plugin.contract}; this platform has contract "
                       f"{CONTRACT_VERSION} (docs/robots.md)")
    problem = settings_problem(plugin.settings)
    if problem is not None:
        return refused(problem)
    return RobotEntry(name, package, version, first.value, plugin)


def find(name: str) -> RobotEntry | None:
    """The installed robot called ``name`` (usable or not), ``None`` when there is none."""
    return _shipped().get(name) or _plugin_entry(name)


def installed() -> tuple[RobotEntry, ...]:
    """Every installed robot: the shipped ones, then the plug-ins by name (each imported)."""
    plugins = [entry for name in sorted(_entry_points()) if (entry := _plugin_entry(name)) is not None]
    return (*_shipped().values(), *plugins)


def usable_names() -> tuple[str, ...]:
    """The names of the robots a study may name."""
    return tuple(entry.name for entry in installed() if entry.problem is None)


def entry(name: str) -> RobotEntry:
    """The usable robot called ``name``; :class:`RobotUnavailable` naming the robots there are, or why this one
    cannot be used."""
    found = find(name)
    if found is None:
        raise RobotUnavailable(f"unknown robot {name!r}; choose one of: {', '.join(usable_names())}")
    found.usable()
    return found


def build(name: str, layout: Layout, rules: Rules, setup: RobotSetup = RobotSetup()) -> Robot:
    """A fresh robot called ``name`` for one trial (a :class:`RobotFactory`)."""
    return entry(name).usable().build(layout, rules, setup.person, dict(setup.settings))


def forget() -> None:
    """Discover again on the next call (a test that changed what is installed)."""
    for cached in (_shipped, _entry_points, _plugin_entry):
        cached.cache_clear()
