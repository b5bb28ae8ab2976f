"""Behaviour 2's wait for the person's view, scored on one predicted future (docs/domain.md §5, "The person's
knowing"): how many ticks of the robot's walk with the dish the person would see if the robot went on now, or
waited ``k`` ticks where it stands and then took the same walk ``k`` ticks later, the person's predicted poses
unchanged. The ticks waited count for nothing, seen or not: a wait is for the walk to be seen, not for standing in
view. The robot weighs these gains over its hypotheses and decides (:meth:`planner.qmdp.QmdpRobot.wait_for_view`).
"""

from __future__ import annotations

from collections.abc import Sequence

from planner.fov import view
from planner.layout import Layout
from planner.objects import DISH
from planner.state import AgentState, WorldState


def wait_gains(layout: Layout, angle: float, robot: AgentState, worlds: Sequence[WorldState], budget: int,
               price: float, garnish: bool) -> list[float] | None:
    """For each wait ``k`` in 0 … ``budget``: the ticks of the dish walk in the person's view after waiting ``k``
    ticks, less ``price`` per tick waited. ``robot`` is the robot now and ``worlds`` the predicted world after each
    coming tick. ``None`` when this future has no dish walk to show (no future at all, the robot never holds the
    dish, or, ``garnish``, the robot does not take the ready garnish onto its plated steak at once)."""
    if not worlds:
        return None
    held = [(robot.pos, robot.held)] + [(w.robot.pos, w.robot.held) for w in worlds]
    people = [view(layout, w.human.pos, w.human.facing, angle).cells for w in worlds]
    trip = [t for t in range(1, len(held)) if held[t][1] == DISH]
    if not trip or (garnish and held[1][1] != DISH):
        return None
    end = trip[-1] + 1
    gains = []
    for k in range(budget + 1):
        seen = 0
        for t in range(k + 1, end + k):  # the walk after the wait: waiting in view is no gain
            pos, holding = held[t - k]
            if holding == DISH and pos in people[min(t, len(people)) - 1]:
                seen += 1
        gains.append(seen - price * k)
    return gains
