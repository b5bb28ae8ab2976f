"""The FOV-aware robots' first move (docs/domain.md §5 step 2): exploration of how the robot's moves change what the
person knows, and hence what they do next.

Besides the direct move toward the chosen subtask (whose score is the one already computed for ``Q``), the robot
rolls out every other first move on a shortest path and, while the modelled KB does not know what the robot holds,
the show plan (:class:`planner.show_plan.ShowPlan`: the cheapest walk after which the person has seen the robot
``human_delay`` ticks in a row). Each candidate is played as the prefix of the same seeded rollouts of every likely
person subtask, in which the simulated person's KB follows what they see, and re-chooses when it makes their subtask
unavailable; the robot takes the candidate with the most expected team progress (ties: the direct move). That is
the default robot's whole objective: a walk through the person's view is taken only when the rollouts say the
team gets on faster for it.

The showing robot (``fov_aware_showing``) adds, to every candidate's score, ``shown_value`` at the tick the person
comes to know what it holds, and walks its own walks (:class:`planner.showing_walks.ShowingWalks`): with a dish (or
a plated steak at a ready garnish) the dish walk, and while the KB is wrong about its hands the hands walk.
"""

from __future__ import annotations

from planner.geometry import Action
from planner.layout import Layout
from planner.moment import Moment
from planner.objects import DISH
from planner.paths import best_moves, distance
from planner.rollout import RobotTasker
from planner.show_plan import ShowPlan
from planner.showing_walks import ShowingWalks
from planner.subtasks import Subtask
from planner.valuation import Valuation, Values


class Exploration:
    """One robot's first moves: ``walks`` only for the showing robot."""

    def __init__(self, layout: Layout, tasker: RobotTasker, valuation: Valuation, show: ShowPlan,
                 walks: ShowingWalks | None) -> None:
        self.layout, self.tasker, self.valuation, self.show, self.walks = layout, tasker, valuation, show, walks

    def first_move(self, m: Moment, subtask: Subtask, values: Values) -> tuple[Action, int]:
        """The first action toward ``subtask`` and how many candidates were explored (0: the direct move alone)."""
        world = m.world
        default = self.valuation.rollout(m).robot_move(world, subtask, m.parked)
        if not m.explores:
            return default, 0
        walks = self.walks
        if walks is not None:
            garnish = (default is Action.INTERACT and subtask is Subtask.PICKUP_GARNISH
                       and walks.at_ready_garnish(world))
            if garnish or (world.robot.held == DISH and subtask is Subtask.DELIVER_DISH and default is not Action.STAY):
                plan = walks.dish_walk(m, subtask, garnish)
                if plan:
                    return plan[0], len(m.likely)
        if default is Action.INTERACT:
            return default, 0
        cells = self.tasker.targets(subtask, world)
        if walks is not None and m.kb.robot is not None and m.kb.robot.held != world.robot.held:
            walk = walks.hands_walk(m, subtask, cells, self.show)
            if walk:
                return walk[0], len(m.likely)
        candidates: dict[Action, tuple[Action, ...]] = {default: ()}
        pose = (world.robot.pos, world.robot.facing)
        if cells:
            nearest = min(cells, key=lambda c: distance(self.layout, pose, c))
            for move in best_moves(self.layout, pose, nearest, world.human.pos):
                candidates.setdefault(move, ())
        show = self.show.plan(world, m.kb, cells)
        if show:
            candidates[show[0]] = show[1:]
        plans = list(candidates.items())
        if len(plans) < 2:
            return default, 0
        knowing = walks is not None and self.valuation.knowing
        scored: list[tuple[float, bool, int]] = []
        for i, (move, rest) in enumerate(plans):
            if scored and m.late():
                break
            direct = move is default and not rest
            if direct:
                v = values.value[subtask] + sum(p * values.known.get((subtask, s), 0.0) for s, p in m.likely)
            else:
                v = sum(p * self.valuation.sampled(m, s, subtask, (move,) + rest, knowing) for s, p in m.likely)
            scored.append((v, direct, i))
        move, rest = plans[max(scored, key=lambda t: (t[0], t[1]))[2]]
        self.show.keep(rest, world)
        return move, len(scored)
