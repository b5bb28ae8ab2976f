"""The dish route through the person's view (paper §VI-C, "a longer path … to stay visible"; docs/domain.md §5,
"The person's knowing"): among the walks to a station at most ``detour`` ticks longer than the shortest, the
one with the most ticks in the person's current view.

A walk is a sequence of moves (a move into a non-floor cell only turns the agent, so it also serves as a
tick of waiting); it avoids the person's cell and ends on a pose from which the robot can interact with one of
the target cells. Ties keep the shorter walk. Pure: the caller gives the cells in view
(:func:`planner.fov.view`).
"""

from __future__ import annotations

from planner.geometry import DIRECTIONS, Action, Pos, move_action
from planner.layout import Layout
from planner.paths import Pose, distance, next_pose


def view_route(layout: Layout, start: Pose, cells: tuple[Pos, ...], seen: frozenset[Pos], person: Pos,
               detour: int) -> tuple[Action, ...]:
    """The moves of the walk (module docstring); empty when no such walk passes a cell in ``seen`` or the
    robot is already at its station."""

    def to_target(pose: Pose) -> int:
        return min(distance(layout, pose, c) for c in cells)

    base = to_target(start)
    if base == 0 or detour < 0:
        return ()
    layer: dict[Pose, tuple[int, tuple[Action, ...]]] = {start: (0, ())}
    best: tuple[int, tuple[Action, ...]] | None = None
    for steps in range(1, base + detour + 1):
        nxt: dict[Pose, tuple[int, tuple[Action, ...]]] = {}
        for pose, (count, actions) in layer.items():
            for d in DIRECTIONS:
                after = next_pose(layout, pose, d)
                if after[0] == person or steps + to_target(after) > base + detour:
                    continue
                score = count + (after[0] in seen)
                if after not in nxt or nxt[after][0] < score:
                    nxt[after] = (score, actions + (move_action(d),))
        for pose, (count, actions) in nxt.items():
            if to_target(pose) == 0 and (best is None or count > best[0]):
                best = (count, actions)
        layer = nxt
    return best[1] if best is not None and best[0] > 0 else ()
