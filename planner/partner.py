"""The simulated partner: the human model driving the robot's avatar, a :class:`planner.decision.Robot` like
the planners of :mod:`planner.robots`; the protocol of what plays the human's avatar in a headless trial; a person
who never moves (:class:`StillHuman`); and a simulated person who differs from the robot's model of them
(:class:`Person`: another view, another KB delay, a share of random actions)."""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from planner.adversary import AdversarialHuman, AdversaryConfig
from planner.decision import Decision
from planner.events import Event
from planner.geometry import ACTIONS, Action
from planner.human import HumanMemory, HumanModel
from planner.kb import KnowledgeBase, omniscient_kb
from planner.layout import Layout
from planner.rules import Rules
from planner.state import WorldState


class HumanPolicy(Protocol):
    """What plays the human's avatar in a headless trial: :class:`planner.human.HumanModel` (the simulated
    human) or another partner model (e.g. :class:`planner.adversary.AdversarialHuman`)."""

    def act(self, world: WorldState, kb: KnowledgeBase, memory: HumanMemory,
            rng: np.random.Generator) -> tuple[Action, HumanMemory]: ...


class StillHuman(HumanModel):
    """A person who never moves or acts, standing where they are (a participant who has stopped; the person
    beside a robot that works alone, :mod:`planner.alone`)."""

    def act(self, world: WorldState, kb: KnowledgeBase, memory: HumanMemory,
            rng: np.random.Generator) -> tuple[Action, HumanMemory]:
        return Action.STAY, memory


@dataclass(frozen=True, slots=True)
class ErraticHuman(HumanModel):
    """The simulated person who, on a share ``random_share`` of ticks, takes a random action (any of the six, drawn
    from the person's generator) instead of the model's: a stray key, a wrong turn, a change of mind the model does
    not foresee."""

    random_share: float = 0.0

    def act(self, world: WorldState, kb: KnowledgeBase, memory: HumanMemory,
            rng: np.random.Generator) -> tuple[Action, HumanMemory]:
        action, memory = HumanModel.act(self, world, kb, memory, rng)
        if rng.random() < self.random_share:
            action = ACTIONS[int(rng.integers(len(ACTIONS)))]
        return action, memory


@dataclass(frozen=True, slots=True)
class Person:
    """The simulated person of a headless trial: their field of view (degrees), KB delay (ticks) and share of random
    actions. A robot models the study's person (``PlannerConfig.human_angle`` / ``human_delay``); a :class:`Person`
    that differs from it tests the robot against a person it does not model exactly."""

    angle: float
    delay: int
    random_share: float = 0.0

    def model(self, layout: Layout, rules: Rules) -> HumanPolicy | None:
        """What plays the person's avatar: ``None`` (the simulated person of :func:`planner.play.run_trial`) unless
        they take random actions."""
        return ErraticHuman(layout, rules, random_share=self.random_share) if self.random_share > 0 else None


PARTNERS: tuple[str, ...] = ("simulated", "adversary", "still")
"""The partner models a headless trial can pair a robot with (``benchmarks/planner/no_stall.py``)."""


def partner_model(name: str, layout: Layout, rules: Rules,
                  adversary: AdversaryConfig = AdversaryConfig()) -> HumanPolicy | None:
    """A fresh partner by name: ``None`` for ``simulated`` (the simulated human :func:`planner.play.run_trial`
    plays by default), :class:`planner.adversary.AdversarialHuman` (with ``adversary``) or :class:`StillHuman`.
    Raises ``ValueError`` naming the known partners for an unknown name."""
    if name not in PARTNERS:
        raise ValueError(f"unknown partner {name!r}; known: {', '.join(PARTNERS)}")
    if name == "adversary":
        return AdversarialHuman(layout, rules, adversary)
    return StillHuman(layout, rules) if name == "still" else None


class SimulatedPartner:
    """The simulated human's model driving the robot's avatar, seeing everything (a scripted teammate)."""

    def __init__(self, layout: Layout, rules: Rules) -> None:
        self.model = HumanModel(layout, rules, me="robot")
        self.memory = HumanMemory()

    def reset(self, world: WorldState, kb: KnowledgeBase | None = None) -> None:
        self.memory = HumanMemory()

    def act(self, world: WorldState, events: Sequence[Event], rng: np.random.Generator) -> Action:
        action, self.memory = self.model.act(world, omniscient_kb(world), self.memory, rng)
        return action

    def decide(self, world: WorldState, events: Sequence[Event], rng: np.random.Generator,
               deadline: float | None = None) -> Decision:
        start = time.perf_counter()
        action = self.act(world, events, rng)
        return Decision(action, elapsed_ms=(time.perf_counter() - start) * 1000)
