"""One decision's situation, frozen (docs/domain.md §5): what every part of a QMDP robot's decision reads.

The robot (:class:`planner.qmdp.QmdpRobot`) keeps what lasts from tick to tick: its model of the person, its own
subtask and its standoff, cycle and flicker watches. Each tick it builds one :class:`Moment` from them, and the parts
of the decision (:mod:`planner.valuation`, :mod:`planner.exploration`, :mod:`planner.showing_walks`,
:mod:`planner.giving_way`) take it instead of reading the robot, so a part sees one consistent situation and can be
tested alone.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

from planner.flicker import FlickerWatch
from planner.kb import KnowledgeBase
from planner.state import WorldState
from planner.subtasks import Subtask

TICKS_PER_SUBTASK = 6
"""Rollout ticks per subtask of lookahead (``search_depth`` × this is the horizon)."""


@dataclass(frozen=True, slots=True)
class Moment:
    """One decision: the world the robot plans on (``unaided`` when it plans alone, docs/domain.md §5, "Working
    alone"), the modelled person's KB, the person's likely subtasks with their weights, the rollout seed of this
    tick (common to every candidate), the lookahead in ticks, how long the person has stood in one cell, whether the
    robot plans alone, whether it explores first moves for what the person would come to know, its current
    subtask, its last touch of a counter (:mod:`planner.flicker`) and the decision's deadline
    (``time.perf_counter()``; ``None``: none)."""

    world: WorldState
    kb: KnowledgeBase
    likely: tuple[tuple[Subtask, float], ...]
    seed: int
    horizon: int
    human_still: int
    alone: bool
    explores: bool
    current: Subtask | None
    touches: FlickerWatch
    deadline: float | None = None

    @property
    def parked(self) -> bool:
        """The person has stood still two ticks: the robot walks around them (as the simulated person does)."""
        return self.human_still >= 2

    def late(self) -> bool:
        """The deadline has passed."""
        return self.deadline is not None and time.perf_counter() > self.deadline
