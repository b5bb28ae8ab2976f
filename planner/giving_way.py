"""How a QMDP robot deals with a person in its way (docs/domain.md §5, "Standoffs", "Joint cycles"): the decision's
part that can answer with an action before any subtask is valued.

Every function takes the decision's :class:`planner.moment.Moment` (or, for a joint cycle, which is judged before
the moment is built, the world) and the robot's :class:`Stance` (its subtask and its standoff and cycle watches),
and answers with the new stance: the robot keeps nothing of its own here. The rules themselves live in
:mod:`planner.standoff` and :mod:`planner.cycle`.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

from planner.cycle import CycleWatch, broken
from planner.geometry import DIRECTIONS, Action, Pos, manhattan, move_action
from planner.kb import omniscient_kb
from planner.layout import Layout
from planner.moment import Moment
from planner.planner_config import PlannerConfig
from planner.rollout import RobotTasker, Rollout
from planner.rules import Rules
from planner.standoff import (
    Standoff,
    alternatives,
    arrive,
    beside,
    committed,
    give_up,
    hold_aside,
    in_the_way,
    step_aside,
    take_over,
    unaided,
    visit_done,
    within_reach,
)
from planner.state import WorldState
from planner.subtasks import Subtask, targets


@dataclass(frozen=True, slots=True)
class Stance:
    """What a robot keeps of its own progress between ticks: its current subtask and its standoff and cycle
    watches."""

    current: Subtask | None = None
    standoff: Standoff = field(default_factory=Standoff)
    cycle: CycleWatch = field(default_factory=CycleWatch)


Answer = tuple[Action | None, Stance]
"""An action (``None``: plan as usual) and the stance after it."""


class GivingWay:
    """The giving-way rules of one robot in one kitchen; ``rollout`` walks the robot (its moves are the same in every
    rollout)."""

    def __init__(self, layout: Layout, rules: Rules, config: PlannerConfig, tasker: RobotTasker,
                 rollout: Rollout) -> None:
        self.layout, self.rules, self.cfg, self.tasker, self.rollout = layout, rules, config, tasker, rollout

    def person_cells(self, world: WorldState, person_task: Subtask) -> tuple[Pos, ...]:
        """The cells of the person's most likely subtask."""
        return targets(self.layout, person_task, world, self.rules)

    def break_cycle(self, world: WorldState, stance: Stance, person_task: Subtask) -> Answer:
        """:mod:`planner.cycle`: in a joint cycle the robot yields (steps aside off the person's way, then holds
        still ``cycle_hold`` ticks) and drops its subtask."""
        if world.tick < stance.cycle.hold_until:
            return Action.STAY, stance
        if not stance.cycle.cycling(self.cfg.cycle_returns):
            return None, stance
        cycle = broken(stance.cycle, stance.current, world.tick, self.cfg.cycle_hold)
        return (step_aside(self.layout, world, self.person_cells(world, person_task)),
                replace(stance, current=None, cycle=cycle))

    def around_standoff(self, m: Moment, stance: Stance, person_task: Subtask,
                        options: tuple[Subtask, ...]) -> tuple[tuple[Subtask, ...] | Action, Stance]:
        """:mod:`planner.standoff`: after ``standoff_ticks`` without progress behind the person, the person's
        stalled work (taken over: the move toward it), else a step aside when the robot is in the person's way, else
        the other reachable options, else a step aside. A person who has not moved for ``visit_ticks`` is then
        visited (:meth:`visit_still_person`). While a given-up subtask is avoided the options are the reachable
        others; when there are none the robot holds its place until the person moves. In a team stall (no progress
        for ``stall_ticks``) the options are judged without the person's load and the robot keeps its subtask,
        moving toward the targets it can reach without passing the person when some cannot be (the move)."""
        world, cfg, standoff, cells = m.world, self.cfg, stance.standoff, self.tasker.targets
        if standoff.stuck >= cfg.standoff_ticks:
            standoff = give_up(standoff, stance.current, world.tick, cfg.standoff_ticks)
            choices = alternatives(self.layout, world, options, stance.current, cells)
            taken = take_over(person_task, choices) if m.human_still >= cfg.standoff_ticks else None
            if taken is not None:
                return self.rollout.robot_move(world, taken, True), replace(stance, current=taken, standoff=standoff)
            person_cells = self.person_cells(world, person_task)
            if not choices or in_the_way(self.layout, world, person_cells):
                return (step_aside(self.layout, world, person_cells),
                        replace(stance, current=None, standoff=hold_aside(standoff, world.tick, cfg.standoff_ticks)))
            return choices, replace(stance, standoff=standoff)
        if world.tick < standoff.hold_until:
            return Action.STAY, stance
        visit, stance = self.visit_still_person(m, stance)
        if visit is not None:
            return visit, stance
        current = stance.current
        if stance.standoff.stalled(cfg.stall_ticks):
            options = committed(self.tasker.options(unaided(world), current), current)
            if current is not None and options == (current,):
                goal = self.tasker.targets(current, world)
                clear = within_reach(self.layout, world, goal)
                if clear and clear != goal:
                    return self.rollout.move_to(world, clear, m.parked), stance
        avoided = stance.standoff.avoided(world.tick)
        if avoided is None or avoided not in options:
            return options, stance
        rest = alternatives(self.layout, world, options, avoided, cells)
        return (rest if rest else Action.STAY), stance

    def visit_still_person(self, m: Moment, stance: Stance) -> Answer:
        """:mod:`planner.standoff`, still person: once the person has stood in one cell for ``visit_ticks`` ticks,
        the robot walks to a cell beside it (around it) and holds there ``standoff_ticks`` ticks, once until the
        person moves again; ``None`` when no visit is under way."""
        world, standoff = m.world, stance.standoff
        if m.human_still < self.cfg.visit_ticks or standoff.visited:
            return None, stance
        if beside(world):
            standoff = arrive(standoff, world.tick, self.cfg.standoff_ticks)
            if world.tick < standoff.beside_until:
                return Action.STAY, replace(stance, standoff=standoff)
            return None, replace(stance, standoff=visit_done(standoff))
        move = self.rollout.move_to(world, (world.human.pos,), True)
        if move in (Action.STAY, Action.INTERACT):
            return None, replace(stance, standoff=visit_done(standoff))
        return move, stance

    def yield_if_blocking(self, m: Moment, subtask: Subtask, action: Action) -> Action:
        """The human model's yield rule for the robot: waiting at a station (steak not ready, garnish not chopped)
        next to a person that has not moved for two ticks, it steps aside (the first free move away from them)."""
        world = m.world
        if action is not Action.INTERACT or not self.rollout.robot_model.waiting(subtask, omniscient_kb(world)):
            return action
        if m.human_still < 2 or manhattan(world.robot.pos, world.human.pos) != 1:
            return action
        for d in sorted(DIRECTIONS, key=lambda d: -manhattan(d.ahead(world.robot.pos), world.human.pos)):
            target = d.ahead(world.robot.pos)
            if target in self.layout.floor and target != world.human.pos:
                return move_action(d)
        return action
