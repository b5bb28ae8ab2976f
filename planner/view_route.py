"""The show walk through the person's view (paper §VI-C, "walks alongside the human", "a staircase path";
docs/domain.md §5, the show plan): the cheapest walk toward a station after which the robot has stood
``need`` consecutive ticks in the person's current view.

A tick of the walk is a move or a stay (a move into a non-floor cell only turns the agent); it avoids the
person's cell. Pure: the caller gives the cells in view (:func:`planner.fov.view`). (A dish's walk is planned
on the person's predicted views instead, :mod:`planner.dish_walk`.)
"""

from __future__ import annotations

from planner.geometry import Action, Pos
from planner.layout import Layout
from planner.paths import UNREACHABLE, Pose, nearest_distances, tick_successors


def show_walk(layout: Layout, start: Pose, cells: tuple[Pos, ...], seen: frozenset[Pos], person: Pos, need: int,
              run: int, detour: int) -> tuple[Action, ...]:
    """The cheapest walk after which the robot has stood ``need`` consecutive ticks in ``seen`` (the person's
    current view), so the person can acknowledge what it holds (docs/domain.md §5, the show plan).

    ``run``: the ticks it has already stood in view (its streak in the person's KB). A tick of the walk is a move
    or a stay; a walk that keeps moving toward ``cells`` through the view costs nothing, one that must wait in
    view costs its stays. Among walks whose extra ticks (``steps + d(end, cells) − d(start, cells)``; no cells:
    the steps) are at most ``detour``, the one with the fewest extra ticks, then the fewest steps. It avoids the
    person's cell. Empty when there is none, or when no tick is needed."""
    if run >= need:
        return ()
    nearest = nearest_distances(layout, cells)
    far = UNREACHABLE if cells else 0

    def to_target(pose: Pose) -> int:
        return nearest.get(pose, far)

    base = to_target(start)
    layer: list[tuple[Pose, int, tuple[Action, ...]]] = [(start, run, ())]
    reached = {(start, run)}
    best: tuple[int, int, tuple[Action, ...]] | None = None
    steps = 0
    while layer and steps < base + (detour if best is None else best[0] - 1):  # a longer walk could still win
        steps += 1
        nxt = []
        for pose, streak, actions in layer:
            for action, after in tick_successors(layout)[pose]:
                cell = after[0]
                if cell == person:
                    continue
                state = (after, min(streak + 1, need) if cell in seen else 0)
                if state in reached:
                    continue
                extra = steps + to_target(after) - base
                if extra > detour:
                    continue
                reached.add(state)
                walk = actions + (action,)
                nxt.append((after, state[1], walk))
                if state[1] >= need and (best is None or (extra, steps) < best[:2]):
                    best = (extra, steps, walk)
        layer = nxt
    return best[2] if best is not None else ()
