"""What a QMDP robot's subtasks are worth (docs/domain.md §5, steps 3–4): the team's progress under the robot's model
of the person.

For every subtask ``r`` the robot could take and every likely subtask ``s`` of the person, one seeded rollout of the
joint system (:class:`planner.rollout.Rollout`: the simulated person choosing from the modelled, FOV-limited KB)
scores the discounted increments of the shaping potential; ``Q(b, r) = γ · avg(Σ_s b(s) V(r, s)) + bonus``, where
``avg`` is the running average of the subtask's value over the previous ticks (``value_smoothing``; one rollout per
hypothesis is noisy, and a robot that flips between subtasks on noise can leave the person stuck) and the bonus is
``commitment_bonus`` for the current subtask. Every candidate of one tick uses the same seed (common random
numbers). Beside a person who has stopped the rollouts are the robot's alone (:func:`planner.alone.solo_rollout`).

The showing robot (``knowing``) also keeps, from the same rollouts, what the person would come to know of the robot
(:meth:`planner.rollout.Rollout.knowing`), for its direct move's score (:mod:`planner.exploration`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from planner.alone import solo_rollout
from planner.geometry import Action
from planner.human import HumanMemory
from planner.layout import Layout
from planner.moment import Moment
from planner.planner_config import PlannerConfig
from planner.rollout import Rollout
from planner.rules import Rules
from planner.smoothing import ValueAverages
from planner.subtasks import Subtask


@dataclass(frozen=True, slots=True)
class Values:
    """One decision's values: ``q`` (what the robot chooses by, in the order the options were valued), ``value``
    (``Σ_s b(s) V(r, s)`` before averaging), ``known`` (the showing robot's knowing value per (robot subtask, person
    subtask)) and whether the deadline cut the valuation short."""

    q: dict[Subtask, float] = field(default_factory=dict)
    value: dict[Subtask, float] = field(default_factory=dict)
    known: dict[tuple[Subtask, Subtask], float] = field(default_factory=dict)
    timed_out: bool = False

    def ranked(self, options: tuple[Subtask, ...], current: Subtask | None) -> list[Subtask]:
        """The valued options, best first (ties: the current subtask, then the options' order)."""
        return sorted(self.q, key=lambda r: (-self.q[r], r is not current, options.index(r)))


class Valuation:
    """The rollouts of one robot (the team's, and the robot's alone), and the running averages of its values."""

    def __init__(self, layout: Layout, rules: Rules, config: PlannerConfig, knowing: bool) -> None:
        self.cfg, self.knowing = config, knowing
        self.team = Rollout(layout, rules, config)
        self.solo = solo_rollout(layout, rules, config)
        self.averages = ValueAverages(config.value_smoothing)

    def rollout(self, m: Moment) -> Rollout:
        """The rollouts of this decision: the robot alone beside a person who has stopped, else the team's."""
        return self.solo if m.alone else self.team

    def sampled(self, m: Moment, human_subtask: Subtask, robot_subtask: Subtask, prefix: tuple[Action, ...] = (),
                knowing: bool = False) -> float:
        """One seeded rollout's value (``prefix``: the robot's first actions; ``knowing``: plus the person's knowing,
        the showing robot's exploration)."""
        return self.rollout(m).value(m.world, m.kb, human_subtask, robot_subtask, m.horizon, m.seed, prefix=prefix,
                                     parked_for=m.human_still, knowing=knowing)

    def parts(self, m: Moment, human_subtask: Subtask, robot_subtask: Subtask) -> tuple[float, float]:
        """The progress and the knowing value of one rollout apart (the showing robot's subtask values: the subtask
        is chosen on the progress alone, the knowing kept for its direct move)."""
        return self.rollout(m).parts(m.world, m.kb, HumanMemory(subtask=human_subtask, held=m.world.human.held),
                                     np.random.default_rng(m.seed), robot_subtask, m.horizon,
                                     parked_for=m.human_still, knowing=True)

    def options(self, m: Moment, options: tuple[Subtask, ...]) -> Values:
        """The values of ``options`` (stops at the deadline once one is valued)."""
        q: dict[Subtask, float] = {}
        value: dict[Subtask, float] = {}
        known: dict[tuple[Subtask, Subtask], float] = {}
        keep_knowing = self.knowing and m.explores
        for r in options:
            if q and m.late():
                return Values(q, value, known, timed_out=True)
            total = 0.0
            for s, p in m.likely:
                if keep_knowing:
                    progress, known[(r, s)] = self.parts(m, s, r)
                else:
                    progress = self.sampled(m, s, r)
                total += p * progress
            value[r] = total
            q[r] = self.cfg.gamma * self.averages.fold(r, total) + (
                self.cfg.commitment_bonus if r is m.current else 0.0)
        return Values(q, value, known)
