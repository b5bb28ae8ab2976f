"""Rollouts kept from one tick to the next (docs/domain.md §5, "Cheaper decisions").

Each tick the QMDP robot values every (robot subtask ``r``, human subtask ``s``) pair by one rollout of
``horizon`` ticks. When the real world then moves exactly as that rollout predicted for its first tick
(same world, same modelled KB, the simulated person still on ``s``, the robot still on ``r``, the person
still parked or not), the rest of the rollout *is* a rollout of ``(r, s)`` from the new state, a sample from
the same model. The robot keeps it: it drops the first tick, simulates one more at the end (same horizon),
and re-uses the sum, so a followed prediction costs one simulated tick instead of ``horizon``. (One
difference to a fresh rollout: the simulated person keeps its memory of the last tick, e.g. how long it has
been stuck, where a fresh rollout starts it with none.) About half of the rollouts are followed on the
shipped kitchens.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from planner.human import HumanMemory
from planner.kb import KnowledgeBase
from planner.rollout import Rollout, SimState
from planner.state import WorldState
from planner.subtasks import Subtask


@dataclass(frozen=True, slots=True)
class Trace:
    """One rollout: the state before each simulated tick, each tick's increment of Φ, the state after the
    last tick and the random stream it continues with (``None`` when the orders were done: nothing to add)."""

    states: tuple[SimState, ...]
    gains: tuple[float, ...]
    end: SimState
    rng: np.random.Generator | None

    @property
    def length(self) -> int:
        """Ticks it covers ahead (a finished trace covers any horizon)."""
        return len(self.gains) if self.rng is not None else 1 << 30

    def value(self, tick_discount: float, horizon: int) -> float:
        """The discounted sum of the first ``horizon`` ticks' increments."""
        total, discount = 0.0, 1.0
        for gain in self.gains[:horizon]:
            total += discount * gain
            discount *= tick_discount
        return total


def traced(rollout: Rollout, world: WorldState, kb: KnowledgeBase, human_subtask: Subtask, robot_subtask: Subtask,
           horizon: int, seed: int, parked_for: int) -> Trace:
    """The rollout of :meth:`planner.rollout.Rollout.value` (same seed, same value), kept as a trace."""
    rng = np.random.default_rng(seed)
    sim = rollout.start(world, kb, HumanMemory(subtask=human_subtask, held=world.human.held), robot_subtask,
                        parked_for)
    states: list[SimState] = []
    gains: list[float] = []
    for _ in range(horizon):
        states.append(sim)
        sim, gain = rollout.tick(sim, rng)
        gains.append(gain)
        if sim.world.orders_left == 0:
            return Trace(tuple(states), tuple(gains), sim, None)
    return Trace(tuple(states), tuple(gains), sim, rng)


def follow(rollout: Rollout, trace: Trace, world: WorldState, kb: KnowledgeBase, human_subtask: Subtask,
           robot_subtask: Subtask, parked_for: int) -> Trace | None:
    """``trace`` one tick on, if the world went as it predicted (see the module doc); else ``None``. The
    trace's random stream is consumed."""
    if len(trace.states) < 2:
        return None
    nxt = trace.states[1]
    if (nxt.world != world or nxt.memory.subtask is not human_subtask or nxt.robot_task is not robot_subtask
            or (nxt.human_still >= 2) != (parked_for >= 2) or (not rollout.omniscient and nxt.kb != kb)):
        return None
    states, gains, end = trace.states[1:], trace.gains[1:], trace.end
    if trace.rng is None:
        return Trace(states, gains, end, None)
    after, gain = rollout.tick(end, trace.rng)
    return Trace(states + (end,), gains + (gain,), after, None if after.world.orders_left == 0 else trace.rng)
