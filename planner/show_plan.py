"""The show plan, one of the FOV-aware robots' explored first moves (docs/domain.md §5 step 2), and the rest of it
the robot follows.

While the modelled person's KB does not know what the robot holds (a load they have not seen it take, or empty hands
after a put-down they did not see), one candidate of the exploration is the cheapest walk toward the robot's station
after which the robot has stood ``human_delay`` consecutive ticks in the person's current view
(:func:`planner.view_route.show_walk`): through the view on the way when it can, else into it and waiting there, at
most ``detour`` ticks longer than the direct way. Whether it is taken is the exploration's choice
(:mod:`planner.exploration`), not this module's; once taken, the robot keeps to it while the person neither moves nor
turns and the KB still does not know (:meth:`ShowPlan.follow`), then plans anew.
"""

from __future__ import annotations

from planner.fov import view
from planner.geometry import Action, Direction, Pos
from planner.kb import ROBOT_KEY, KnowledgeBase
from planner.layout import Layout
from planner.objects import DISH
from planner.state import WorldState
from planner.view_route import show_walk


class ShowPlan:
    """The show plan of one robot in one trial: ``detour`` extra ticks at most, for a person seeing ``angle``
    degrees who acknowledges after ``delay`` consecutive ticks in view."""

    def __init__(self, layout: Layout, angle: float, delay: int, detour: int) -> None:
        self.layout, self.angle, self.delay, self.detour = layout, angle, delay, detour
        self.pending: tuple[Action, ...] = ()
        self.pending_person: tuple[Pos, Direction] | None = None

    def reset(self) -> None:
        """A trial starts or resumes, or the robot gives way: nothing to follow."""
        self.pending = ()

    def follow(self, world: WorldState, kb: KnowledgeBase) -> Action | None:
        """The next action of the plan being followed, while the modelled KB still does not know what the robot
        holds and the person has neither moved nor turned since it was made; ``None`` when there is none to follow
        (the robot decides anew)."""
        held = world.robot.held
        if self.pending and held != DISH and kb.robot is not None and kb.robot.held != held and (
                (world.human.pos, world.human.facing) == self.pending_person):
            action, self.pending = self.pending[0], self.pending[1:]
            return action
        return None

    def keep(self, rest: tuple[Action, ...], world: WorldState) -> None:
        """Follow ``rest`` from the next tick while the person stays as they are in ``world``."""
        self.pending = rest
        self.pending_person = (world.human.pos, world.human.facing)

    def plan(self, world: WorldState, kb: KnowledgeBase, cells: tuple[Pos, ...]) -> tuple[Action, ...]:
        """The cheapest walk toward ``cells`` (a subtask's targets; none: anywhere) after which the robot has stood
        ``delay`` consecutive ticks in the person's current view (the ticks it already stands in view, its streak in
        the modelled KB, count). Empty when the KB already knows what the robot holds or no such walk exists."""
        if kb.robot is None or kb.robot.held == world.robot.held:
            return ()
        human = world.human
        seen = view(self.layout, human.pos, human.facing, self.angle).cells
        return show_walk(self.layout, (world.robot.pos, world.robot.facing), cells, seen, human.pos, self.delay,
                         self.streak(world, kb), self.detour)

    def streak(self, world: WorldState, kb: KnowledgeBase) -> int:
        """The ticks the robot has stood in the person's view holding what it holds now: its streak in the
        modelled KB ``kb``, 0 when it is out of the person's current view."""
        human, held = world.human, world.robot.held
        if world.robot.pos not in view(self.layout, human.pos, human.facing, self.angle).cells:
            return 0
        return next((n for key, occupant, n in kb.streaks if key == ROBOT_KEY and occupant == held), 0)
