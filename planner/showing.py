"""What the FOV-aware robot keeps between ticks for showing itself (docs/domain.md §5, "The person's knowing").

The plans that show the robot to the person and their state: the show plan (:func:`planner.view_route.show_walk`)
and the rest of it the robot is following (``pending``, kept while the person neither moves nor turns), the dish
trip, its detour budget and its ticks in the person's view so far (behaviour 2's dish walk,
:mod:`planner.dish_walk`), and this decision's value of the person's knowing per (robot subtask, person's
subtask), kept from the rollouts that valued the subtasks for the direct move (``known``), and the hands walk's
leg and its detour budget (:meth:`Showing.leg_budget`, :mod:`planner.hands_walk`). Which plan the robot
takes is the robot's choice (:meth:`planner.qmdp.QmdpRobot.first_move`), not this module's.
"""

from __future__ import annotations

from planner.fov import view
from planner.geometry import Action, Direction, Pos
from planner.kb import ROBOT_KEY, KnowledgeBase
from planner.layout import Layout
from planner.objects import DISH, STEAK_PLATE
from planner.paths import UNREACHABLE, nearest_distances
from planner.planner_config import PlannerConfig
from planner.state import WorldState
from planner.subtasks import Subtask
from planner.view_route import show_walk


class Showing:
    """The showing state of one robot in one trial."""

    def __init__(self, layout: Layout, config: PlannerConfig) -> None:
        self.layout, self.cfg = layout, config
        self.pending: tuple[Action, ...] = ()
        self.pending_person: tuple[Pos, Direction] | None = None
        self.dish_trip: tuple[int, int] | None = None
        self.known: dict[tuple[Subtask, Subtask], float] = {}
        self.trip_seen = (0, 0)
        """The ticks of the robot's dish trip so far with it in the person's view, and in all."""
        self.leg: tuple[tuple[str | None, tuple[Pos, ...]], int, int] | None = None
        """The hands walk's leg (:meth:`leg_budget`): what the robot holds and the cells it walks to, the tick it
        began and the shortest way then."""

    def reset(self) -> None:
        """A trial starts or resumes: nothing pending, no dish trip."""
        self.pending = ()
        self.dish_trip = None
        self.leg = None
        self.trip_seen = (0, 0)

    def observe(self, world: WorldState) -> None:
        """A dish trip ends when the robot no longer carries a dish (or the plated steak it waits with at a ready
        garnish, :meth:`trip_detour_left`); while it carries one, each tick counts toward :attr:`trip_seen`."""
        if world.robot.held not in (DISH, STEAK_PLATE):
            self.dish_trip = None
        if world.robot.held == DISH:
            seen = world.robot.pos in view(self.layout, world.human.pos, world.human.facing, self.cfg.human_angle).cells
            self.trip_seen = (self.trip_seen[0] + seen, self.trip_seen[1] + 1)
        else:
            self.trip_seen = (0, 0)

    def follow(self, world: WorldState, kb: KnowledgeBase) -> Action | None:
        """The next action of the show plan being followed, while the modelled KB still does not know what the
        robot holds and the person has neither moved nor turned since it was made; ``None`` when there is none
        to follow (the robot decides anew; with a dish, always: the dish walk is planned every tick)."""
        held = world.robot.held
        if self.pending and held != DISH and kb.robot is not None and kb.robot.held != held and (
                (world.human.pos, world.human.facing) == self.pending_person):
            action, self.pending = self.pending[0], self.pending[1:]
            return action
        return None

    def start(self, world: WorldState, garnish: bool = False) -> None:
        """A new decision: nothing pending, no knowing value yet; a dish trip's clock starts at its first decision
        (:meth:`begin_trip`; ``garnish``: the robot is about to take a ready garnish)."""
        self.pending = ()
        self.known = {}
        self.begin_trip(world, garnish)

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

    def keep(self, rest: tuple[Action, ...], world: WorldState) -> None:
        """Follow ``rest`` from the next tick while the person stays as they are in ``world``."""
        self.pending = rest
        self.pending_person = (world.human.pos, world.human.facing)

    def show_plan(self, world: WorldState, kb: KnowledgeBase | None, cells: tuple[Pos, ...]) -> tuple[Action, ...]:
        """The cheapest walk toward ``cells`` (a subtask's targets; none: anywhere) after which the robot has stood
        ``human_delay`` consecutive ticks in the person's current view, so the person acknowledges what it holds
        (paper §VI-C, "walks alongside the human"; :func:`planner.view_route.show_walk`): through the view on the
        way when it can, else into it and waiting there, at most ``view_detour + human_delay − 1`` ticks longer
        than the direct way. The ticks it already stands in view (its streak in the modelled KB ``kb``) count.
        Empty when the modelled KB already knows what the robot holds or no such walk exists."""
        if kb is None or kb.robot is None or kb.robot.held == world.robot.held:
            return ()
        human = world.human
        seen = view(self.layout, human.pos, human.facing, self.cfg.human_angle).cells
        need = self.cfg.human_delay
        return show_walk(self.layout, (world.robot.pos, world.robot.facing), cells, seen, human.pos, need,
                         self.streak(world, kb), self.show_detour)

    @property
    def show_detour(self) -> int:
        """The most extra ticks of a walk that shows the robot's hands: ``view_detour`` and the ticks in view
        beyond the first (``human_delay − 1``)."""
        return self.cfg.view_detour + max(self.cfg.human_delay - 1, 0)

    def streak(self, world: WorldState, kb: KnowledgeBase) -> int:
        """The ticks the robot has stood in the person's view holding what it holds now: its streak in the
        modelled KB ``kb``, 0 when it is out of the person's current view."""
        human, held = world.human, world.robot.held
        if world.robot.pos not in view(self.layout, human.pos, human.facing, self.cfg.human_angle).cells:
            return 0
        return next((n for key, occupant, n in kb.streaks if key == ROBOT_KEY and occupant == held), 0)

    def leg_budget(self, world: WorldState, cells: tuple[Pos, ...], shortest: int) -> int:
        """The extra ticks the hands walk (:mod:`planner.hands_walk`) may still take on its leg: the robot's way,
        holding what it holds now, to ``cells`` (``shortest`` ticks from where it stands). A leg gets
        ``view_detour`` extra ticks in all (a dish trip ``dish_detour``); the ticks it has taken beyond its shortest
        way so far count against them, so the robot cannot wait in view tick after tick. A new leg begins when the
        robot's hands or its cells change."""
        key = (world.robot.held, cells)
        if self.leg is None or self.leg[0] != key:
            self.leg = (key, world.tick, shortest)
        _, began, shortest_then = self.leg
        return max(self.detour_left(world.tick, began, shortest_then, shortest, self.cfg.view_detour), 0)

    def trip_detour_left(self, world: WorldState, garnish: bool = False) -> int:
        """The ticks the robot's dish trip (:meth:`begin_trip`) may still spend beyond its shortest way
        (``dish_detour`` for the whole trip, docs/domain.md §5, "The person's knowing"): the extra ticks the dish has
        taken so far (ticks since it was taken less how much shorter the way to the serving counter has become)
        count against it, so the robot cannot wait in view tick after tick. ``garnish``: the robot holds a plated
        steak and is about to take a ready garnish; the trip starts there, so the ticks it waits before taking it
        count too. 0 when no trip runs, it carries no dish (nor stands at a ready garnish) or stands at the
        counter."""
        if self.dish_trip is None or not self.carries_dish(world, garnish):
            return 0
        shortest = self.shortest_to_serve(world)
        if shortest == 0:
            return 0
        began, shortest_then = self.dish_trip
        return self.detour_left(world.tick, began, shortest_then, shortest, self.cfg.dish_detour)

    @staticmethod
    def detour_left(tick: int, began: int, shortest_then: int, shortest: int, limit: int) -> int:
        """What is left of ``limit`` extra ticks on a way begun at tick ``began`` ``shortest_then`` ticks from its
        goal and now, at ``tick``, ``shortest`` ticks from it: the ticks since it began less how much closer it has
        come are the extra ticks taken (never more than ``limit``; negative when it has taken more)."""
        return min(limit, limit - (tick - began - (shortest_then - shortest)))

    def walk_budget(self, world: WorldState, garnish: bool = False) -> int:
        """The extra ticks the dish walk may still take (or, ``garnish``, spend before and after taking a ready
        garnish onto its plated steak): what is left of the trip's detour (:meth:`trip_detour_left`), at least 0."""
        return max(self.trip_detour_left(world, garnish), 0)
