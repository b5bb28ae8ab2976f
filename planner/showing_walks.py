"""The showing robot's walks (``fov_aware_showing``; docs/domain.md §5, "The showing robot"): the dish walk and the
hands walk, planned on the person's predicted poses, with the detour budgets that bound them.

Only the showing robot walks these: the default FOV-aware robot takes a first move only for the team's progress
(:mod:`planner.exploration`). What is kept between ticks here: the dish trip (the tick it began and its shortest way
then, behaviour 2's ticks in the person's view so far) and the hands walk's leg (what the robot holds, the cells it
walks to, the tick it began and its shortest way then). The walks themselves are pure programmes
(:func:`planner.dish_walk.dish_walk`, :func:`planner.hands_walk.hands_walk`); the person's poses come from one
rollout per likely subtask of theirs (:func:`predicted_poses`, the robot going on with its own subtask), weighted by
the belief.
"""

from __future__ import annotations

import numpy as np

from planner.dish_walk import Future, dish_walk
from planner.fov import view
from planner.geometry import Action, Pos
from planner.hands_walk import hands_walk
from planner.human import HumanMemory
from planner.layout import Layout
from planner.moment import Moment
from planner.objects import DISH, STEAK_PLATE
from planner.paths import UNREACHABLE, nearest_distances
from planner.planner_config import PlannerConfig
from planner.rollout import Rollout
from planner.rules import Rules
from planner.show_plan import ShowPlan
from planner.state import WorldState
from planner.subtasks import Subtask


def predicted_poses(rollout: Rollout, m: Moment, human_subtask: Subtask, robot_subtask: Subtask,
                    ticks: int) -> list[tuple[Pos, object]]:
    """The person's (cell, facing) after each of the next ``ticks`` ticks of the rollout of one hypothesis (the
    rollout of the subtask values with this tick's seed), until the orders are done."""
    rng = np.random.default_rng(m.seed)
    sim = rollout.start(m.world, m.kb, HumanMemory(subtask=human_subtask, held=m.world.human.held), robot_subtask,
                        m.human_still)
    poses: list[tuple[Pos, object]] = []
    for _ in range(ticks):
        sim, _ = rollout.tick(sim, rng)
        poses.append((sim.world.human.pos, sim.world.human.facing))
        if sim.world.orders_left == 0:
            break
    return poses


def detour_left(tick: int, began: int, shortest_then: int, shortest: int, limit: int) -> int:
    """What is left of ``limit`` extra ticks on a way begun at tick ``began`` ``shortest_then`` ticks from its goal
    and now, at ``tick``, ``shortest`` ticks from it: the ticks since it began less how much closer it has come are
    the extra ticks taken (never more than ``limit``; negative when it has taken more)."""
    return min(limit, limit - (tick - began - (shortest_then - shortest)))


class ShowingWalks:
    """The showing robot's dish trip and hands walk in one trial."""

    def __init__(self, layout: Layout, rules: Rules, config: PlannerConfig, rollout: Rollout) -> None:
        self.layout, self.rules, self.cfg, self.rollout = layout, rules, config, rollout
        self.dish_trip: tuple[int, int] | None = None
        self.trip_seen = (0, 0)
        """The ticks of the robot's dish trip so far with it in the person's view, and in all."""
        self.leg: tuple[tuple[str | None, tuple[Pos, ...]], int, int] | None = None
        """The hands walk's leg (:meth:`leg_budget`): what the robot holds and the cells it walks to, the tick it
        began and the shortest way then."""

    def reset(self) -> None:
        """A trial starts or resumes: no dish trip, no leg."""
        self.dish_trip = None
        self.leg = None
        self.trip_seen = (0, 0)

    def observe(self, world: WorldState) -> None:
        """A dish trip ends when the robot no longer carries a dish (or the plated steak it waits with at a ready
        garnish); while it carries one, each tick counts toward :attr:`trip_seen`."""
        if world.robot.held not in (DISH, STEAK_PLATE):
            self.dish_trip = None
        if world.robot.held == DISH:
            seen = world.robot.pos in view(self.layout, world.human.pos, world.human.facing, self.cfg.human_angle).cells
            self.trip_seen = (self.trip_seen[0] + seen, self.trip_seen[1] + 1)
        else:
            self.trip_seen = (0, 0)

    def at_ready_garnish(self, world: WorldState) -> bool:
        """The robot holds a plated steak and faces a board with a chopped garnish: an interact makes the dish."""
        if world.robot.held != STEAK_PLATE:
            return False
        faced = world.robot.facing.ahead(world.robot.pos)
        return any(cell == faced and self.rules.chopped(status)
                   for cell, status in zip(self.layout.boards, world.boards, strict=True))

    def begin_trip(self, world: WorldState, garnish: bool = False) -> None:
        """Start the dish trip's clock if the robot carries a dish (or, ``garnish``, stands with a plated steak at a
        ready garnish: the dish is held from the next tick on) away from the serving counter and no trip runs."""
        if self.dish_trip is not None or not self.carries_dish(world, garnish):
            return
        shortest = self.shortest_to_serve(world)
        if shortest:
            self.dish_trip = (world.tick + (world.robot.held == STEAK_PLATE), shortest)

    def carries_dish(self, world: WorldState, garnish: bool) -> bool:
        """The robot carries a dish, or (``garnish``) a plated steak at a ready garnish, in a kitchen that serves."""
        held = world.robot.held
        return bool(self.layout.serves) and (held == DISH or (garnish and held == STEAK_PLATE))

    def shortest_to_serve(self, world: WorldState) -> int:
        """The ticks of the robot's shortest way to deliver at a serving counter from where it stands."""
        return nearest_distances(self.layout, self.layout.serves).get((world.robot.pos, world.robot.facing),
                                                                      UNREACHABLE)

    def leg_budget(self, world: WorldState, cells: tuple[Pos, ...], shortest: int) -> int:
        """The extra ticks the hands walk may still take on its leg: the robot's way, holding what it holds now, to
        ``cells`` (``shortest`` ticks from where it stands). A leg gets ``view_detour`` extra ticks in all; the ticks
        it has taken beyond its shortest way so far count against them, so the robot cannot wait in view tick after
        tick. A new leg begins when the robot's hands or its cells change."""
        key = (world.robot.held, cells)
        if self.leg is None or self.leg[0] != key:
            self.leg = (key, world.tick, shortest)
        _, began, shortest_then = self.leg
        return max(detour_left(world.tick, began, shortest_then, shortest, self.cfg.view_detour), 0)

    def trip_detour_left(self, world: WorldState, garnish: bool = False) -> int:
        """The ticks the dish trip may still spend beyond its shortest way (``dish_detour`` for the whole trip): the
        extra ticks the dish has taken so far count against it. ``garnish``: the robot holds a plated steak and is
        about to take a ready garnish; the trip starts there, so the ticks it waits before taking it count too. 0
        when no trip runs, it carries no dish (nor stands at a ready garnish) or stands at the counter."""
        if self.dish_trip is None or not self.carries_dish(world, garnish):
            return 0
        shortest = self.shortest_to_serve(world)
        if shortest == 0:
            return 0
        began, shortest_then = self.dish_trip
        return detour_left(world.tick, began, shortest_then, shortest, self.cfg.dish_detour)

    def walk_budget(self, world: WorldState, garnish: bool = False) -> int:
        """The extra ticks the dish walk may still take: what is left of the trip's detour, at least 0."""
        return max(self.trip_detour_left(world, garnish), 0)

    def dish_walk(self, m: Moment, subtask: Subtask, garnish: bool) -> tuple[Action, ...]:
        """Behaviour 2's plan for the dish (``garnish``: the robot stands with a plated steak at a ready garnish):
        within what is left of the trip's detour, the walk whose trip the person is expected to see most."""
        world = m.world
        budget = self.walk_budget(world, garnish)
        pose = (world.robot.pos, world.robot.facing)
        shortest = nearest_distances(self.layout, self.layout.serves).get(pose, UNREACHABLE)
        if shortest >= UNREACHABLE:
            return ()
        futures = self.futures(m, subtask, shortest + budget + 2)  # as far as the programme looks, the interact too
        return dish_walk(self.layout, self.cfg.human_angle, pose, futures, budget, self.cfg.walk_price, garnish,
                         self.trip_seen)

    def hands_walk(self, m: Moment, subtask: Subtask, cells: tuple[Pos, ...], show: ShowPlan) -> tuple[Action, ...]:
        """The way to ``cells`` that shows the person what the robot holds, within what is left of the leg's detour:
        the person's poses predicted as for the dish walk, and, for a person who has stood in one cell ``n`` ticks,
        the hypothesis that they keep their pose, weighted ``n / (n + hands_still)``."""
        world = m.world
        pose = (world.robot.pos, world.robot.facing)
        shortest = nearest_distances(self.layout, cells).get(pose, UNREACHABLE)
        if shortest == 0 or shortest >= UNREACHABLE:
            return ()
        budget = self.leg_budget(world, cells, shortest)
        futures = self.kept_pose(m, self.futures(m, subtask, shortest + budget))
        return hands_walk(self.layout, self.cfg.human_angle, pose, cells, futures, self.cfg.human_delay,
                          show.streak(world, m.kb), budget, self.cfg.hands_price)

    def futures(self, m: Moment, subtask: Subtask, ticks: int) -> list[Future]:
        """The person's poses over the next ``ticks`` ticks, one hypothesis per likely subtask of theirs, weighted by
        the belief (the robot going on with ``subtask``)."""
        return [(p, predicted_poses(self.rollout, m, s, subtask, ticks)) for s, p in m.likely]  # type: ignore[misc]

    def kept_pose(self, m: Moment, futures: list[Future]) -> list[Future]:
        """``futures`` and, for a person who has stood in one cell ``n`` ticks, the hypothesis that they keep their
        pose, weighted ``n / (n + hands_still)``: the longer a person has stood, the likelier they stay."""
        if not m.human_still:
            return futures
        kept = m.human_still / (m.human_still + self.cfg.hands_still)
        world = m.world
        return [(p * (1 - kept), poses) for p, poses in futures] + [(kept, [(world.human.pos, world.human.facing)])]
