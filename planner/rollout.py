"""Lookahead for the robot planners: the joint system simulated forward with the human model.

A rollout starts from the real world, the robot's model of the human's KB and a hypothesised human
subtask. The simulated human follows that subtask, then chooses anew from *its modelled KB* exactly as
:class:`planner.human.HumanModel` does (FOV-limited for the FOV-aware robot, omniscient for the baseline),
its KB updated every tick by the same FOV rules, so the robot entering its view, or working out of it,
changes what it predicts the person will do. The robot follows a candidate subtask, then picks the
available subtask nearest to it that the human is not already doing.

Value of a rollout: the discounted sum of the increments of the shaping potential Φ (docs/domain.md §5 step 4,
the reference's rewards): Φ = −40 per order left (+100 when none is), +5 per steak on a grill,
+(3 + count) per board and per sink in use, +12 / +20 / +30 per clean plate / plated steak / dish held
*or on a counter* (the reference counted only held ones; then putting a plate down to free the hands
looks like lost work and the robot would rather block a station than step away).
Progress made sooner is worth more (``tick_discount`` per tick).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from planner.events import EventKind
from planner.geometry import Action, Pos
from planner.human import HumanMemory, HumanModel
from planner.kb import KnowledgeBase, omniscient_kb, update_kb
from planner.layout import Layout
from planner.objects import CLEAN_PLATE, DISH, MEAT, ONION, STEAK_PLATE
from planner.paths import UNREACHABLE, distances_to
from planner.planner_config import PlannerConfig
from planner.rules import Rules
from planner.state import WorldState
from planner.step import step
from planner.subtasks import (
    Believed,
    Subtask,
    available,
    beyond_orders,
    finished,
    resumable,
    resumed_targets,
    targets,
    within_orders,
)


def potential(world: WorldState, cfg: PlannerConfig) -> float:
    value = cfg.order_left_penalty * world.orders_left
    if world.orders_left == 0:
        value += cfg.all_done_reward
    value += cfg.steak_on_grill * sum(g is not None for g in world.grills)
    value += sum(cfg.station_in_use + b for b in world.boards if b is not None)
    value += sum(cfg.station_in_use + s for s in world.sinks if s is not None)
    for held in (world.human.held, world.robot.held, *(obj for _, obj in world.objects)):
        if held == CLEAN_PLATE:
            value += cfg.hold_clean_plate
        elif held == STEAK_PLATE:
            value += cfg.hold_steak
        elif held == DISH:
            value += cfg.hold_dish
    return value


@dataclass(frozen=True, slots=True)
class RobotTasker:
    """The robot's own subtask logic, judged on the world (the robot sees everything)."""

    layout: Layout
    rules: Rules

    def options(self, world: WorldState, current: Subtask | None) -> tuple[Subtask, ...]:
        """The human's options (docs/domain.md §4) from the robot's seat, plus what only someone who sees the whole
        kitchen would add: finishing an onion or plate left unfinished; putting a plated steak down
        while no garnish is ready (else both agents can end up waiting on a board nobody chops, or the
        robot waiting in the only spot from which the human could bring the onion); and fetching a clean
        plate (then the steak) as soon as a steak *and* a garnish are on their way, counting the meat or
        onion the human carries, instead of only once both are on their stations (the human's rule judges
        by its KB, the robot sees the human's hands).
        """
        return _robot_options(self.rules, world.robot.held, world.human.held, world.orders_left, world.objects,
                              world.grills, world.boards, world.sinks, current)

    def done(self, subtask: Subtask, held_before: str | None, world: WorldState) -> bool:
        return finished(subtask, held_before, world.robot.held, world.boards, world.sinks, self.rules)

    def targets(self, subtask: Subtask, world: WorldState) -> tuple[Pos, ...]:
        if world.robot.held is None and subtask in (Subtask.PICKUP_STEAK, Subtask.PICKUP_GARNISH):
            return resumed_targets(subtask, world.objects)
        return targets(self.layout, subtask, world, self.rules)

    def nearest(self, world: WorldState, options: tuple[Subtask, ...], avoid: Subtask | None) -> Subtask:
        pose = (world.robot.pos, world.robot.facing)
        best, best_d = options[0], UNREACHABLE + 1
        for s in options:
            d = min((distances_to(self.layout, c).get(pose, UNREACHABLE) for c in self.targets(s, world)),
                    default=UNREACHABLE)
            if s is avoid and len(options) > 1:
                d += UNREACHABLE // 2
            if d < best_d:
                best, best_d = s, d
        return best


@lru_cache(maxsize=1 << 15)
def _robot_options(rules: Rules, held: str | None, human_held: str | None, orders_left: int,
                   objects: tuple[tuple[Pos, str], ...], grills: tuple[int | None, ...], boards: tuple[int | None, ...],
                   sinks: tuple[int | None, ...], current: Subtask | None) -> tuple[Subtask, ...]:
    """:meth:`RobotTasker.options` from the parts of the world it reads (not the agents' poses), cached: every
    rollout tick asks it, mostly about the same few kitchens."""
    b = Believed(kb=KnowledgeBase(objects=objects, grills=grills, boards=boards, sinks=sinks, robot=None),
                 held=held, partner_held=human_held, orders_left=orders_left)
    options = list(available(b, rules, current))
    unchopped = any(rules.chopping(v) for v in boards)
    unwashed = any(rules.washing(v) for v in sinks)
    if held is None:
        if unchopped and Subtask.CHOP_ONION not in options:
            options.append(Subtask.CHOP_ONION)
        if unwashed and Subtask.WASH_PLATE not in options:
            options.append(Subtask.WASH_PLATE)
    elif (held == STEAK_PLATE and not any(rules.chopped(v) for v in boards)
          and Subtask.DROP_ON_COUNTER not in options):
        options.append(Subtask.DROP_ON_COUNTER)
    coming = ((any(g is not None for g in grills) or human_held == MEAT)
              and (any(v is not None for v in boards) or human_held == ONION))
    if coming and held is None and Subtask.PICKUP_CLEAN_PLATE not in options:
        if (any(rules.clean(v) for v in sinks)
                or any(obj == CLEAN_PLATE for _, obj in objects)):
            options.append(Subtask.PICKUP_CLEAN_PLATE)
    elif coming and held == CLEAN_PLATE and Subtask.PICKUP_STEAK not in options:
        options.append(Subtask.PICKUP_STEAK)
    options += resumable(held, objects, boards, rules)
    return within_orders(tuple(options), beyond_orders(held, human_held, orders_left, objects, grills, boards, sinks))


@dataclass(frozen=True, slots=True)
class SimState:
    """The simulated joint system between two rollout ticks."""

    world: WorldState
    kb: KnowledgeBase
    memory: HumanMemory
    robot_task: Subtask | None
    human_still: int
    phi: float


class Rollout:
    """Simulates the joint system for one (robot subtask, human subtask) hypothesis."""

    def __init__(self, layout: Layout, rules: Rules, cfg: PlannerConfig) -> None:
        self.layout, self.rules, self.cfg = layout, rules, cfg
        self.human = HumanModel(layout, rules, me="human")
        self.robot_model = HumanModel(layout, rules, me="robot")
        self.tasker = RobotTasker(layout, rules)
        self.omniscient = cfg.human_sees_everything

    def value(self, world: WorldState, kb: KnowledgeBase, human_subtask: Subtask, robot_subtask: Subtask,
              horizon: int, seed: int, prefix: tuple[Action, ...] = (), parked_for: int = 0,
              knowing: bool = False) -> float:
        """The discounted progress of the hypothesis; the robot plays ``prefix`` first, then its subtask.
        ``knowing``: each tick also adds :meth:`knowing`."""
        return self.run(world, kb, HumanMemory(subtask=human_subtask, held=world.human.held),
                        np.random.default_rng(seed), robot_subtask, horizon, prefix, parked_for, knowing)

    def run(self, world: WorldState, kb: KnowledgeBase, memory: HumanMemory, rng: np.random.Generator,
            robot_subtask: Subtask, horizon: int, prefix: tuple[Action, ...] = (), parked_for: int = 0,
            knowing: bool = False) -> float:
        """:meth:`value` from a given human memory and random stream (``rng`` is consumed)."""
        progress, known = self.parts(world, kb, memory, rng, robot_subtask, horizon, prefix, parked_for, knowing)
        return progress + known

    def parts(self, world: WorldState, kb: KnowledgeBase, memory: HumanMemory, rng: np.random.Generator,
              robot_subtask: Subtask, horizon: int, prefix: tuple[Action, ...] = (), parked_for: int = 0,
              knowing: bool = False) -> tuple[float, float]:
        """:meth:`run`'s two sums apart: the discounted progress, and the discounted :meth:`knowing` (0 unless
        ``knowing``), so one rollout serves a subtask's value and its first move's."""
        sim = self.start(world, kb, memory, robot_subtask, parked_for)
        total, known, discount = 0.0, 0.0, 1.0
        knowing = knowing and not self.omniscient
        showing: str | None = world.robot.held
        still_showing = True
        for t in range(horizon):
            before = sim
            sim, gain = self.tick(sim, rng, prefix[t] if t < len(prefix) else None)
            if knowing:
                known += discount * self.knowing(before, sim.world, sim.kb, showing, still_showing)
                still_showing = still_showing and sim.world.robot.held == showing
            total += discount * gain
            discount *= self.cfg.tick_discount
            if sim.world.orders_left == 0:
                break
        return total, known

    def start(self, world: WorldState, kb: KnowledgeBase, memory: HumanMemory, robot_subtask: Subtask,
              parked_for: int = 0) -> SimState:
        return SimState(world, kb, memory, robot_subtask, parked_for, potential(world, self.cfg))

    def tick(self, sim: SimState, rng: np.random.Generator,
             robot_action: Action | None = None) -> tuple[SimState, float]:
        """One tick of the simulated joint system: the next state and the increment of Φ. The robot takes
        ``robot_action`` if given, else its move toward its subtask."""
        world, kb, robot_task, human_still = sim.world, sim.kb, sim.robot_task, sim.human_still
        h_action, memory = self.human.act(world, kb, sim.memory, rng)
        if robot_task is None:
            robot_task = self.tasker.nearest(world, self.tasker.options(world, None), memory.subtask)
        r_action = robot_action if robot_action is not None else self.robot_move(world, robot_task, human_still >= 2)
        human_before = world.human.pos
        held_before = world.robot.held
        world, events = step(self.layout, world, {"human": h_action, "robot": r_action}, self.rules)
        if self.omniscient:
            kb = omniscient_kb(world)
        else:
            kb = update_kb(kb, self.layout, world, angle=self.cfg.human_angle,
                           kb_delay=self.cfg.human_delay,
                           own_events=[e for e in events if e.agent == "human"])
        human_still = human_still + 1 if world.human.pos == human_before else 0
        # Φ reads only what interactions change (cooking moves a grill's count, not whether it is used).
        phi = potential(world, self.cfg) if any(e.kind is not EventKind.BLOCKED for e in events) else sim.phi
        next_task: Subtask | None = robot_task
        if self.tasker.done(robot_task, held_before, world) or robot_task not in self.tasker.options(world, robot_task):
            next_task = None
        return SimState(world, kb, memory, next_task, human_still, phi), phi - sim.phi

    def knowing(self, before: SimState, world: WorldState, kb: KnowledgeBase, showing: str | None,
                still_showing: bool = True) -> float:
        """The showing robot's value of what the modelled person comes to know of it this tick (docs/domain.md §5,
        "The showing robot"): ``shown_value`` at the tick their KB acknowledges ``showing`` (the object the robot
        held when the decision was made; ``still_showing``: it has held it ever since). Zero for empty hands and for
        a person who sees everything. Only what the robot holds now earns it: a cost for every unknown load in the
        lookahead made the robot avoid and delay work (measured, docs/changes.md, "Measurement history")."""
        held = world.robot.held
        if held is None or not still_showing or held != showing or kb.robot is None or kb.robot.held != held:
            return 0.0
        return self.cfg.shown_value if before.kb.robot is None or before.kb.robot.held != held else 0.0

    def robot_move(self, world: WorldState, subtask: Subtask, human_parked: bool = False) -> Action:
        """The robot's next move toward ``subtask`` (walking around a human parked for two ticks)."""
        return self.move_to(world, self.tasker.targets(subtask, world), human_parked)

    def move_to(self, world: WorldState, cells: tuple[Pos, ...], human_parked: bool = False) -> Action:
        """The robot's next move toward the nearest of ``cells`` (as :meth:`robot_move`)."""
        pose = (world.robot.pos, world.robot.facing)
        action, _ = self.robot_model.move_toward(pose, cells, world.human.pos, partner_parked=human_parked)
        return action
