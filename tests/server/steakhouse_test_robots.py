"""Robot factories for the server tests, importable by spawned worker processes (same ``sys.path``).

Each is ``factory(name, layout, rules, setup) -> policy`` like ``planner.robot_catalog.build``.
"""

from __future__ import annotations

import os
import time
from collections.abc import Sequence
from typing import Any

import numpy as np

from planner.decision import Decision
from planner.events import Event
from planner.geometry import Action
from planner.kb import KnowledgeBase
from planner.partner import SimulatedPartner
from planner.robot_catalog import RobotSetup
from planner.state import WorldState


def simulated_partner(name: str, layout: Any, rules: Any, config: Any = None) -> SimulatedPartner:
    """The simulated human's model driving the robot: it moves all over the kitchen (``act`` only)."""
    return SimulatedPartner(layout, rules)


class Counting:
    """Stateful: answers north on its 1st, 3rd, … decision and south on the others; ``q_values`` carry the
    count, so a test sees whether every decision of a trial reached the same planner object."""

    def __init__(self) -> None:
        self.calls = 0
        self.pid = os.getpid()

    def reset(self, world: WorldState, kb: KnowledgeBase | None = None) -> None:
        self.calls = 0

    def decide(self, world: WorldState, events: Sequence[Event], rng: np.random.Generator,
               deadline: float | None = None) -> Decision:
        self.calls += 1
        return Decision(Action.NORTH if self.calls % 2 else Action.SOUTH,
                        q_values={"calls": float(self.calls), "pid": float(self.pid)})


def counting(name: str, layout: Any, rules: Any, config: Any = None) -> Counting:
    return Counting()


class Slow(Counting):
    """Takes ``SLOW_S`` seconds per decision, ignoring the deadline."""

    def decide(self, world: WorldState, events: Sequence[Event], rng: np.random.Generator,
               deadline: float | None = None) -> Decision:
        time.sleep(float(os.environ.get("STEAKHOUSE_TEST_SLOW_S", "0.3")))
        return super().decide(world, events, rng, deadline)


def slow(name: str, layout: Any, rules: Any, config: Any = None) -> Slow:
    return Slow()


class Failing(Counting):
    def decide(self, world: WorldState, events: Sequence[Event], rng: np.random.Generator,
               deadline: float | None = None) -> Decision:
        raise ValueError("planner bug")


def failing(name: str, layout: Any, rules: Any, config: Any = None) -> Failing:
    return Failing()


class Crashing(Counting):
    """Kills its worker process on its third decision."""

    def decide(self, world: WorldState, events: Sequence[Event], rng: np.random.Generator,
               deadline: float | None = None) -> Decision:
        if self.calls == 2:
            os._exit(3)
        return super().decide(world, events, rng, deadline)


def crashing(name: str, layout: Any, rules: Any, config: Any = None) -> Crashing:
    return Crashing()


def unbuildable(name: str, layout: Any, rules: Any, config: Any = None) -> Counting:
    raise ImportError(f"planner {name!r} is not installed")


class ConfigEcho(Counting):
    """Answers with the model of the person it was built with and whether the KB it was reset with knows
    where the robot is (in ``q_values``), so a test sees what reached a worker process."""

    def __init__(self, setup: RobotSetup) -> None:
        super().__init__()
        self.setup = setup
        self.kb: KnowledgeBase | None = None

    def reset(self, world: WorldState, kb: KnowledgeBase | None = None) -> None:
        super().reset(world, kb)
        self.kb = kb

    def decide(self, world: WorldState, events: Sequence[Event], rng: np.random.Generator,
               deadline: float | None = None) -> Decision:
        knows_robot = -1.0 if self.kb is None else float(self.kb.robot is not None)
        person = self.setup.person
        return Decision(Action.STAY, q_values={"angle": person.fov_angle, "delay": float(person.kb_delay),
                                               "kb_robot": knows_robot})


def config_echo(name: str, layout: Any, rules: Any, setup: RobotSetup) -> ConfigEcho:
    return ConfigEcho(setup)


class GcProbe(Counting):
    """Answers with the number of objects its process has frozen out of the cyclic garbage collector."""

    def decide(self, world: WorldState, events: Sequence[Event], rng: np.random.Generator,
               deadline: float | None = None) -> Decision:
        import gc

        return Decision(Action.STAY, q_values={"frozen": float(gc.get_freeze_count())})


def gc_probe(name: str, layout: Any, rules: Any, config: Any = None) -> GcProbe:
    return GcProbe()
