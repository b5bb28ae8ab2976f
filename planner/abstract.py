"""Heuristic search over abstract states (docs/domain.md §5 steps 3–4; paper §V-B, §V-C).

**Abstraction.** A reached state keeps the stations' statuses, the objects on counters, the orders left,
what each agent holds and the subtask each is doing; the human's FOV is removed (its KB is the world from
here on). Where an agent is matters only through the cost function: an agent is known by the pose it
started its subtask from and the ticks it has already walked (``elapsed``), and after a subtask it stands
at the station it used.

**Transitions** are events: both agents work on their subtasks at once and the next abstract state is
reached when the first of them finishes (the paper: "the smallest number of steps required for either the
robot to reach [its station] or the human to reach [its station]"). An agent's time to finish is its
shortest-path distance to the nearest target of its subtask (precomputed, :mod:`planner.paths`) less what
it has walked, plus the presses the station still needs (chop, wash) or the cook time still to run
(pickup steak). The finisher's effect is applied with the world's own rules (:func:`planner.step.step`),
the grills cook meanwhile, and the finisher picks its next subtask: the robot the best of its options
(max), the human one of its available subtasks at random (the simulated human's rule; expectation).

**Value** of a state searched to depth ``n``: ``V = Σ_d discount^d (ΔΦ_d − C_d)`` with ``C_d`` the ticks
of the d-th transition and ``ΔΦ_d`` the change of the shaping potential (the reference's rewards,
:func:`planner.rollout.potential`). Successors are computed lazily and cached per abstract state (a
bounded dictionary; no transition matrices).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from planner.geometry import Action, Pos, manhattan
from planner.kb import omniscient_kb
from planner.layout import Layout, Terrain
from planner.paths import UNREACHABLE, Pose, distances_to
from planner.planner_config import PlannerConfig
from planner.rollout import RobotTasker, potential
from planner.rules import Rules
from planner.state import AgentState, WorldState
from planner.step import step
from planner.subtasks import Believed, Subtask, available, targets

CACHE_LIMIT = 200_000
WAITING = 10**4
"""Finish time of a subtask that waits on the other agent (a plated steak for a garnish nobody has chopped)."""
STALEMATE = -100.0
"""Value of a state where both agents wait on each other."""


@dataclass(frozen=True, slots=True)
class Job:
    """An agent's subtask in an abstract state: ``None`` = choosing; ``elapsed`` = ticks already walked."""

    task: Subtask | None
    elapsed: int = 0


@dataclass(frozen=True, slots=True)
class AbstractState:
    world: WorldState
    robot: Job
    human: Job

    @classmethod
    def of(cls, world: WorldState, robot: Subtask | None, human: Subtask | None) -> AbstractState:
        """The abstraction of a reached state (the tick and score do not matter to what follows)."""
        return cls(replace(world, tick=0, score=0), Job(robot), Job(human))

    def job(self, name: str) -> Job:
        return self.robot if name == "robot" else self.human


class AbstractSearch:
    """``value(state)``: the best discounted progress reachable in ``depth`` abstract transitions."""

    def __init__(self, layout: Layout, rules: Rules, cfg: PlannerConfig) -> None:
        self.layout, self.rules, self.cfg = layout, rules, cfg
        self.tasker = RobotTasker(layout, rules)
        self.cache: dict[tuple[AbstractState, int], float] = {}

    def leaf(self, world: WorldState, robot: Subtask | None, human: Subtask | None) -> float:
        """The value of a state an exploration reached (:mod:`planner.reference`): subtasks already done
        or no longer available are chosen anew."""
        if robot is not None and robot not in self.tasker.options(world, robot):
            robot = None
        if human is not None and human not in self.human_options(world, human):
            human = None
        return self.value(AbstractState.of(world, robot, human))

    def value(self, state: AbstractState, depth: int | None = None) -> float:
        depth = self.cfg.abstract_depth if depth is None else depth
        if depth <= 0 or state.world.orders_left == 0:
            return 0.0
        key = (state, depth)
        cached = self.cache.get(key)
        if cached is not None:
            return cached
        if state.robot.task is None:
            result = max(self.value(replace(state, robot=Job(r)), depth)
                         for r in self.tasker.options(state.world, None))
        elif state.human.task is None:
            options = self.human_options(state.world)
            result = sum(self.value(replace(state, human=Job(h)), depth) for h in options) / len(options)
        elif self.stalemate(state):
            result = STALEMATE
        else:
            after, cost = self.transition(state)
            gain = potential(after.world, self.cfg) - potential(state.world, self.cfg) - cost
            result = gain + self.cfg.abstract_discount * self.value(after, depth - 1)
        if len(self.cache) >= CACHE_LIMIT:
            self.cache.clear()
        self.cache[key] = result
        return result

    def human_options(self, world: WorldState, current: Subtask | None = None) -> tuple[Subtask, ...]:
        b = Believed(kb=omniscient_kb(world), held=world.human.held, partner_held=world.robot.held,
                     orders_left=world.orders_left)
        return available(b, self.rules, current)

    def stalemate(self, state: AbstractState) -> bool:
        return all(self.finish_time(state.world, name, state.job(name))[0] >= WAITING for name in ("robot", "human"))

    def transition(self, state: AbstractState) -> tuple[AbstractState, int]:
        """The next event: whichever agent finishes first (the robot on ties) does its subtask; the cost
        is the ticks that took."""
        world = state.world
        r_time, r_cell = self.finish_time(world, "robot", state.robot)
        h_time, h_cell = self.finish_time(world, "human", state.human)
        if r_time <= h_time:
            name, cell, dt = "robot", r_cell, r_time
        else:
            name, cell, dt = "human", h_cell, h_time
        other = "human" if name == "robot" else "robot"
        presses = self.presses(world, state.job(name).task, cell) if cell is not None else 0
        world = _cook(world, dt - presses, self.rules.cook_time)
        if cell is not None:
            world = world.with_agent(name, AgentState(*_stand(self.layout, world.agent(name), cell),
                                                      world.agent(name).held))
            idle = {other: Action.STAY}
            for _ in range(presses):
                world, _events = step(self.layout, world, {name: Action.INTERACT, **idle}, self.rules)
        world = replace(world, tick=0, score=0)
        done = Job(None)
        later = replace(state.job(other), elapsed=state.job(other).elapsed + dt)
        jobs = {name: done, other: later}
        return AbstractState(world, robot=jobs["robot"], human=jobs["human"]), dt

    def finish_time(self, world: WorldState, name: str, job: Job) -> tuple[int, Pos | None]:
        """Ticks until ``name`` finishes ``job`` and the station it uses (``(0, None)``: nothing to do)."""
        if job.task is None:
            return 0, None
        agent = world.agent(name)
        pose: Pose = (agent.pos, agent.facing)
        best, walk = None, UNREACHABLE
        for cell in targets(self.layout, job.task, omniscient_kb(world), self.rules):
            d = distances_to(self.layout, cell).get(pose, UNREACHABLE)
            if d < walk:
                best, walk = cell, d
        if best is None:
            return 0, None
        walk = max(walk - job.elapsed, 0)
        presses = self.presses(world, job.task, best)
        if job.task is Subtask.PICKUP_GARNISH and not self.rules.chopped(_status(self.layout, world, best)):
            return WAITING, best
        if job.task is Subtask.PICKUP_STEAK:
            status = _status(self.layout, world, best)
            walk = max(walk, self.rules.cook_time - (status or 0))
        return walk + presses, best

    def presses(self, world: WorldState, task: Subtask | None, cell: Pos) -> int:
        """Interacts the subtask takes at ``cell``: the chops or washes still to do, else one."""
        status = _status(self.layout, world, cell) or 0
        if task is Subtask.CHOP_ONION:
            return max(self.rules.chop_time - status, 1)
        if task is Subtask.WASH_PLATE:
            return max(self.rules.wash_time - status, 1)
        return 1


def _status(layout: Layout, world: WorldState, cell: Pos) -> int | None:
    entry = layout.stations.get(cell)
    if entry is None:
        return None
    kind, i = entry
    statuses = {Terrain.GRILL: world.grills, Terrain.BOARD: world.boards, Terrain.SINK: world.sinks}.get(kind)
    return None if statuses is None else statuses[i]


def _cook(world: WorldState, ticks: int, cook_time: int) -> WorldState:
    if ticks <= 0 or not any(g is not None and g < cook_time for g in world.grills):
        return world
    return replace(world, grills=tuple(None if g is None else min(g + ticks, cook_time) for g in world.grills))


def _stand(layout: Layout, agent: AgentState, cell: Pos) -> Pose:
    """Where an agent ends up to use ``cell``: the pose facing it, nearest to where it was."""
    poses = [pose for pose, d in distances_to(layout, cell).items() if d == 0]
    return min(poses, key=lambda p: (manhattan(p[0], agent.pos), p[0], p[1].value))
