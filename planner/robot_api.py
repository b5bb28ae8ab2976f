"""The robot plug-in contract, version 1 (docs/robots.md): everything a robot of another package may use.

A package registers a :class:`RobotPlugin` under the entry-point group ``steakhouse.robots``
(:mod:`planner.robot_catalog`); a study names it like any robot. The plug-in is a factory: given the kitchen
(:class:`Layout`), its numbers (:class:`Rules`), what the study tells every robot about the person
(:class:`Person`) and the robot's own settings (an instance of its declared ``settings`` dataclass, the study's
``robot_variants`` settings checked against it), it returns a fresh :class:`Robot` for one trial.

The robot reads the true world (:class:`WorldState`: both agents' poses and held objects, every station and
counter, orders left, tick, score) and the last step's :class:`Event` s, and it answers a :class:`Decision` by the
deadline. It never gets anything of the participant the robot could not know in the paper's setting: not the
subtask they chose, not their keys, not who they are or which condition they are in. Its randomness comes from
the generator it is handed (one stream per trial and tick: same seed, same decisions).

A change to anything here that breaks a plug-in written for it raises :data:`CONTRACT_VERSION`; the catalogue
refuses a plug-in written for another version, with the reason.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Generic, TypeVar

from planner.decision import Decision, Robot
from planner.events import Event, EventKind
from planner.geometry import ACTIONS, Action, Direction, Pos
from planner.kb import KnowledgeBase
from planner.layout import Layout, Terrain
from planner.perception import FOV_ANGLE, KB_DELAY
from planner.rules import Rules
from planner.state import AgentState, WorldState

__all__ = [
    "ACTIONS", "CONTRACT_VERSION", "Action", "AgentState", "Decision", "Direction", "Event", "EventKind",
    "KnowledgeBase", "Layout", "NoSettings", "Person", "Pos", "Robot", "RobotPlugin", "Rules", "Terrain",
    "WorldState", "settings_problem",
]

CONTRACT_VERSION = 1
"""The version of this contract. A plug-in says which one it was written for (:attr:`RobotPlugin.contract`)."""

S = TypeVar("S")


@dataclass(frozen=True, slots=True)
class Person:
    """What the study tells every robot about the person it works with (docs/domain.md §5): the trial's field of
    view in degrees (the study's ``world.fov_angle``, or the trial's level of ``fov_angles``) and the study's KB
    delay in ticks (``world.kb_delay``). The shipped FOV-aware robot models the person with them; the baseline
    ignores them (it models a person who sees everything)."""

    fov_angle: float = FOV_ANGLE
    kb_delay: int = KB_DELAY


@dataclass(frozen=True, slots=True)
class NoSettings:
    """The settings of a robot that has none."""


@dataclass(frozen=True, slots=True)
class RobotPlugin(Generic[S]):
    """A robot factory with its declared settings. ``make(kitchen, rules, person, settings)`` returns a fresh
    :class:`Robot` for one trial; ``settings`` is a dataclass whose fields all have defaults (the robot's
    settings, typed: a study's ``robot_variants`` may change them, each checked by name and type); ``contract``
    is the :data:`CONTRACT_VERSION` it was written for; ``summary`` one line for ``steakhouse robots``."""

    make: Callable[[Layout, Rules, Person, S], Robot]
    settings: type[S]
    contract: int = CONTRACT_VERSION
    summary: str = ""

    def __call__(self, kitchen: Layout, rules: Rules, person: Person, settings: S) -> Robot:
        return self.make(kitchen, rules, person, settings)

    def build(self, kitchen: Layout, rules: Rules, person: Person, values: dict[str, Any]) -> Robot:
        """A robot with ``values`` (already checked: ``study_config/study/robots.py``) over the defaults."""
        return self.make(kitchen, rules, person, self.settings(**values))


def settings_problem(settings: object) -> str | None:
    """Why ``settings`` cannot be a plug-in's declared settings (``None`` when it can): a dataclass type whose
    fields all have defaults (a study may name the robot without settings)."""
    if not (isinstance(settings, type) and dataclasses.is_dataclass(settings)):
        return f"its settings must be a dataclass type, not {settings!r}"
    missing = [f.name for f in dataclasses.fields(settings)
               if f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING]
    if missing:
        return f"its settings need a default for every field ({', '.join(missing)} have none)"
    return None
