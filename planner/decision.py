"""What a robot planner answers each tick (a :class:`Decision`: the action and a record of how it chose, for
logs and the admin view), and the one interface every robot offers (:class:`Robot`), used alike by the
server's robot pools, :mod:`planner.play` and the simulation. Both are part of the plug-in contract
(:mod:`planner.robot_api`, docs/robots.md); robots are built by :func:`planner.robot_catalog.build`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from planner.events import Event
from planner.geometry import Action
from planner.kb import KnowledgeBase
from planner.state import WorldState


@dataclass(frozen=True, slots=True)
class Decision:
    action: Action
    q_values: dict[str, float] = field(default_factory=dict)
    belief: dict[str, float] = field(default_factory=dict)
    explored_kbs: int = 0
    elapsed_ms: float = 0.0
    timed_out: bool = False
    cycle_broken: bool = False
    """The robot yielded this tick to break a joint cycle with the person (:mod:`planner.cycle`)."""

    def to_dict(self) -> dict[str, object]:
        return {
            "action": self.action.value,
            "q_values": {k: round(v, 3) for k, v in self.q_values.items()},
            "belief": {k: round(v, 4) for k, v in self.belief.items()},
            "explored_kbs": self.explored_kbs,
            "elapsed_ms": round(self.elapsed_ms, 3),
            "timed_out": self.timed_out,
            "cycle_broken": self.cycle_broken,
        }


class Robot(Protocol):
    """A robot policy for one trial. ``reset`` starts it on the world the trial starts or resumes from;
    ``decide`` is called once per tick with the world after the last step and that step's events. Its
    randomness comes only from ``rng`` (one stream per trial, from the trial's seed: same seed, same
    decisions). ``deadline`` is an absolute ``time.perf_counter()`` value: past it the planner returns its
    best action so far and sets ``timed_out``."""

    def reset(self, world: WorldState, kb: KnowledgeBase | None = None) -> None:
        """Start on ``world``. ``kb`` is the person's modelled KB at ``world`` (docs/domain.md §3) when a trial
        resumes mid-way (the server's restored KB); ``None`` at a trial's first world, where the person's KB is
        :func:`planner.kb.initial_kb`. A robot that models the person's KB starts its model from it (unless
        its model is another person's, e.g. the baseline's omniscient one)."""

    def decide(self, world: WorldState, events: Sequence[Event], rng: np.random.Generator,
               deadline: float | None = None) -> Decision: ...

