"""An adversarial participant: a partner model that tests whether a robot ever stalls.

It plays the human's avatar with the participant's own means (docs/domain.md §4: choosing subtasks, or
interrupt actions) but against the team, in phases drawn from the generator passed in:

* ``random_task`` – walks to and works on a subtask drawn uniformly from *all* subtasks, including those
  that are impossible now (delivering with empty hands, garnishing without a plated steak, …), pressing
  interact when it gets there;
* ``block``       – walks to the access cell of a station with the fewest access cells (the *only* access
  cell where a kitchen has one) and stands there;
* ``interrupt``   – random actions (any of the six) every tick;
* ``idle``        – stands still for a long stretch;
* ``cooperate``   – plays as the simulated human (:class:`planner.human.HumanModel`).

**When the task stays possible.** A person who blocks the only access cell of a station forever makes
the task impossible for any robot, so the disruption is bounded: the adversary spends at most
``AdversaryConfig.budget`` ticks (default 150) in the four disruptive phases; after that it plays as
the simulated human for the rest of the trial. A robot *stalls* when a trial with this partner is still
unfinished at the horizon (docs/domain.md §1: 400 ticks), i.e. it failed to finish in the ≥ 250 ticks
the adversary leaves it, which is far more than a simulated team needs for the whole trial (about 90).
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

import numpy as np

from planner.geometry import ACTIONS, Action, Pos
from planner.human import HumanMemory, HumanModel
from planner.kb import KnowledgeBase
from planner.layout import STATIONS, Layout, access_cells
from planner.paths import Pose
from planner.planner_config import PlannerConfig
from planner.rollout import potential
from planner.rules import Rules
from planner.state import WorldState, initial_state
from planner.step import step
from planner.subtasks import SUBTASKS, Subtask, targets


class Mode(str, Enum):
    RANDOM_TASK = "random_task"
    BLOCK = "block"
    INTERRUPT = "interrupt"
    IDLE = "idle"
    COOPERATE = "cooperate"


DISRUPTIVE: tuple[Mode, ...] = (Mode.RANDOM_TASK, Mode.BLOCK, Mode.INTERRUPT, Mode.IDLE)


@dataclass(frozen=True, slots=True)
class AdversaryConfig:
    """``budget``: disruptive ticks at most, then cooperative for good. ``phase``: (min, max) ticks of a
    phase; ``idle``: (min, max) ticks of a still stretch. ``weights``: how often each mode is drawn, in
    the order of :class:`Mode`."""

    budget: int = 150
    phase: tuple[int, int] = (5, 30)
    idle: tuple[int, int] = (20, 60)
    weights: tuple[float, float, float, float, float] = (0.25, 0.25, 0.15, 0.2, 0.15)

    def __post_init__(self) -> None:
        if self.budget < 0:
            raise ValueError(f"budget must be 0 or more, got {self.budget}")
        for name in ("phase", "idle"):
            low, high = getattr(self, name)
            if not 1 <= low <= high:
                raise ValueError(f"{name} must be (min, max) with 1 <= min <= max, got {(low, high)}")
        if len(self.weights) != len(Mode) or min(self.weights) < 0 or sum(self.weights) <= 0:
            raise ValueError(f"weights must be {len(Mode)} non-negative numbers, not all 0")


class AdversarialHuman:
    """The adversary as a human policy for :func:`planner.play.run_trial` (``human=``): the same
    ``act(world, kb, memory, rng) -> (action, memory)`` as :class:`planner.human.HumanModel`.

    Its phase is its own state (one instance per trial); its randomness is the ``rng`` passed in, so the
    same seed gives the same trial."""

    def __init__(self, layout: Layout, rules: Rules, config: AdversaryConfig = AdversaryConfig()) -> None:
        self.layout, self.rules, self.cfg = layout, rules, config
        self.model = HumanModel(layout, rules)
        self.mode = Mode.COOPERATE
        self.left = 0
        self.spent = 0
        self.subtask: Subtask | None = None
        self.station: Pos | None = None
        self.history: list[Mode] = []
        """The mode of every tick played so far (for tests and reports)."""

    def act(self, world: WorldState, kb: KnowledgeBase, memory: HumanMemory,
            rng: np.random.Generator) -> tuple[Action, HumanMemory]:
        if self.spent >= self.cfg.budget:
            self.mode = Mode.COOPERATE
        elif self.left <= 0:
            self.start_phase(rng)
        self.left -= 1
        self.history.append(self.mode)
        if self.mode is Mode.COOPERATE:
            return self.model.act(world, kb, memory, rng)
        self.spent += 1
        human = world.human
        pose: Pose = (human.pos, human.facing)
        forget = HumanMemory(held=human.held, last_pose=pose)
        if self.mode is Mode.IDLE:
            return Action.STAY, forget
        if self.mode is Mode.INTERRUPT:
            return ACTIONS[int(rng.integers(len(ACTIONS)))], forget
        if self.mode is Mode.BLOCK:
            assert self.station is not None
            action, _ = self.model.move_toward(pose, (self.station,), world.robot.pos, rng)
            return (Action.STAY if action is Action.INTERACT else action), forget
        assert self.subtask is not None
        cells = targets(self.layout, self.subtask, kb, self.rules) or self.layout.counters
        action, _ = self.model.move_toward(pose, cells, world.robot.pos, rng)
        return action, forget

    def start_phase(self, rng: np.random.Generator) -> None:
        weights = np.array(self.cfg.weights, dtype=float)
        self.mode = tuple(Mode)[int(rng.choice(len(Mode), p=weights / weights.sum()))]
        low, high = self.cfg.idle if self.mode is Mode.IDLE else self.cfg.phase
        self.left = int(rng.integers(low, high + 1))
        if self.mode is Mode.RANDOM_TASK:
            self.subtask = SUBTASKS[int(rng.integers(len(SUBTASKS)))]
        elif self.mode is Mode.BLOCK:
            narrow = narrowest_stations(self.layout)
            self.station = narrow[int(rng.integers(len(narrow)))]


def narrowest_stations(layout: Layout) -> tuple[Pos, ...]:
    """The stations (dispensers, grills, boards, sinks, serving counters) with the fewest access cells."""
    cells = [pos for pos, (kind, _) in sorted(layout.stations.items()) if kind in STATIONS]
    counts = {pos: len(access_cells(layout, pos)) for pos in cells}
    fewest = min(c for c in counts.values() if c > 0)
    return tuple(pos for pos in cells if counts[pos] == fewest)


def last_progress_tick(layout: Layout, rules: Rules, actions: tuple[tuple[Action, Action], ...]) -> int:
    """The last tick at which the team made progress, replaying a recorded trial's ``(human, robot)``
    actions: the last change of the shaping potential of :func:`planner.rollout.potential` (orders, steaks
    on grills, boards and sinks in use and their counts, clean plates, plated steaks and dishes anywhere).
    Carrying a dirty plate to a counter and back, or the grill's clock, is no progress. A stalled trial
    stopped there."""
    cfg = PlannerConfig()
    world = initial_state(layout, rules)
    last, phi = 0, potential(world, cfg)
    for human, robot in actions:
        world, _ = step(layout, world, {"human": human, "robot": robot}, rules)
        now = potential(world, cfg)
        if now != phi:
            last, phi = world.tick, now
    return last
