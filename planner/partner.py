"""The simulated partner: the human model driving the robot's avatar, a :class:`planner.decision.Robot` like
the planners of :mod:`planner.robots`; the protocol of what plays the human's avatar in a headless trial; and
a person who never moves (:class:`StillHuman`)."""

from __future__ import annotations

import time
from collections.abc import Sequence
from typing import Protocol

import numpy as np

from planner.adversary import AdversarialHuman, AdversaryConfig
from planner.decision import Decision
from planner.events import Event
from planner.geometry import Action
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
