"""docs/domain.md §5 step by step, as the reference implementation planned (``PlannerConfig(lookahead="abstract")``).

For each low-level robot action ``a`` and each likely human subtask ``s`` (belief ≥ threshold):

1. **one step**: the world steps with ``a`` and the human's predicted move for ``s`` (the human model,
   its modelled KB updated by the FOV rules);
2. **exploration**: robot motion sequences (north/south/east/west/stay) of depth ``k``
   (``exploration_depth``) are played from there, all ``5^k`` of them when that is at most
   ``exploration_samples``, else that many drawn uniformly (seeded); the human follows its model and its
   KB is tracked, so a sequence that enters the human's view can change what it does next;
3. **abstraction** of each reached state (:class:`planner.abstract.AbstractState`: the human's subtask as
   re-predicted from the KB it reached, the FOV dropped from there on);
4. **heuristic search** over abstract states (:class:`planner.abstract.AbstractSearch`, depth ``n`` =
   ``abstract_depth``, discount ``abstract_discount``);
5. ``Q(b, a) = Σ_s b(s) (R(s, a) + γ Σ_s' T(s, a, s') V(s'))`` where ``R`` is the step's shaping
   progress, ``T`` the fraction of explored sequences reaching ``s'`` and ``V(s')`` the sequence's
   progress plus the abstract value of ``s'``. The reference took the maximum over the reached states
   instead (the robot chooses its own follow-up); measured on all kitchens × seeds 10–11 that stalled
   trials at the horizon (FOV-aware robot 163 ticks on average against 111 with the expectation), so
   the expectation is used (``REFERENCE_COMBINE``).

Each explored sequence uses the same human random stream (common random numbers), so actions are
compared on the same futures. Successors of abstract states are computed lazily and cached in the search.
"""

from __future__ import annotations

import itertools
import time

import numpy as np

from planner.abstract import AbstractSearch
from planner.events import Event
from planner.geometry import ACTIONS, MOTIONS, Action
from planner.human import HumanMemory, HumanModel
from planner.kb import KnowledgeBase, update_kb
from planner.layout import Layout
from planner.planner_config import PlannerConfig
from planner.rollout import potential
from planner.rules import Rules
from planner.state import WorldState
from planner.step import step
from planner.subtasks import Subtask

REFERENCE_COMBINE = "mean"


class ReferenceLookahead:
    """``q_values(...)``: Q(b, a) for every low-level robot action by docs/domain.md §5's pipeline."""

    def __init__(self, layout: Layout, rules: Rules, cfg: PlannerConfig) -> None:
        self.layout, self.rules, self.cfg = layout, rules, cfg
        self.human = HumanModel(layout, rules, me="human")
        self.search = AbstractSearch(layout, rules, cfg)

    def sequences(self, rng: np.random.Generator) -> tuple[tuple[Action, ...], ...]:
        k = self.cfg.exploration_depth
        if k <= 0:
            return ((),)
        if len(MOTIONS) ** k <= self.cfg.exploration_samples:
            return tuple(itertools.product(MOTIONS, repeat=k))
        picks = rng.integers(len(MOTIONS), size=(self.cfg.exploration_samples, k))
        return tuple(dict.fromkeys(tuple(MOTIONS[i] for i in row) for row in picks))

    def q_values(self, world: WorldState, kb: KnowledgeBase, likely: tuple[tuple[Subtask, float], ...],
                 seed: int, deadline: float | None = None) -> tuple[dict[Action, float], int, bool]:
        """Q per action, the number of distinct human KBs the exploration reached, and whether the deadline
        cut the search short (then only the actions valued so far are returned; at least one)."""
        sequences = self.sequences(np.random.default_rng(seed))
        q: dict[Action, float] = {}
        kbs: set[KnowledgeBase] = set()
        for action in ACTIONS:
            if deadline is not None and q and time.perf_counter() > deadline:
                return q, len(kbs), True
            total = 0.0
            for subtask, p in likely:
                memory = HumanMemory(subtask=subtask, held=world.human.held)
                h_rng = np.random.default_rng(seed)
                h_action, memory = self.human.act(world, kb, memory, h_rng)
                after, events = step(self.layout, world, {"human": h_action, "robot": action}, self.rules)
                after_kb = self.update(kb, after, events)
                reward = potential(after, self.cfg) - potential(world, self.cfg)
                values = [self.explore(after, after_kb, memory, plan, seed, kbs) for plan in sequences]
                best = max(values) if REFERENCE_COMBINE == "max" else sum(values) / len(values)
                total += p * (reward + self.cfg.gamma * best)
            q[action] = total
        return q, len(kbs), False

    def explore(self, world: WorldState, kb: KnowledgeBase, memory: HumanMemory, plan: tuple[Action, ...],
                seed: int, kbs: set[KnowledgeBase]) -> float:
        """Progress along one motion sequence, then the abstract value of the state it reaches."""
        rng = np.random.default_rng(seed + 1)
        phi = potential(world, self.cfg)
        total, discount = 0.0, 1.0
        for move in plan:
            if world.orders_left == 0:
                return total
            h_action, memory = self.human.act(world, kb, memory, rng)
            world, events = step(self.layout, world, {"human": h_action, "robot": move}, self.rules)
            kb = self.update(kb, world, events)
            new_phi = potential(world, self.cfg)
            total += discount * (new_phi - phi)
            phi, discount = new_phi, discount * self.cfg.tick_discount
        kbs.add(kb)
        # the human's next subtask as re-predicted from the KB it reached, before the FOV is dropped
        subtask = self.human.commit(world, kb, memory, rng)
        return total + discount * self.search.leaf(world, None, subtask)

    def update(self, kb: KnowledgeBase, world: WorldState, events: tuple[Event, ...]) -> KnowledgeBase:
        return update_kb(kb, self.layout, world, angle=self.cfg.human_angle, kb_delay=self.cfg.human_delay,
                         own_events=[e for e in events if e.agent == "human"])
