"""Behaviour 2's dish walk, planned on the person's predicted views (docs/domain.md §5, "The showing robot").

The robot with a dish (or with a plated steak at a ready garnish, about to make the dish) takes, among all walks to
a serving counter at most ``budget`` ticks longer than the shortest (stays included, so waiting where it stands for
the person to turn is one such walk; at a garnish, waiting before taking it too), the one whose dish trip the person
is expected to see the largest share of, less ``price`` per extra tick. The share counts the trip's ticks so far
(``past``) with the planned ones: the measure of behaviour 2 (docs/domain.md §6). The person's view at each coming
tick is predicted, one sequence of poses per hypothesis of what they are doing, weighted by its probability
(:meth:`planner.qmdp.QmdpRobot.predicted_worlds`). A pure dynamic programme over (tick, pose), about
``(shortest + budget) × poses × 5`` steps; the walk never steps into the cell where the most likely hypothesis puts
the person at that tick.
"""

from __future__ import annotations

from collections.abc import Sequence

from planner.fov import view
from planner.geometry import Action, Direction, Pos
from planner.layout import Layout
from planner.paths import UNREACHABLE, Pose, nearest_distances, next_pose, tick_successors

Future = tuple[float, Sequence[tuple[Pos, Direction]]]
"""One hypothesis of what the person does: its probability and their (cell, facing) after each coming tick."""

_Layer = dict[Pose, tuple[float, tuple[Action, ...]]]


def seen_chances(layout: Layout, angle: float, futures: Sequence[Future], ticks: int) -> list[dict[Pos, float]]:
    """For each coming tick 1 … ``ticks`` (index 0 … ``ticks − 1``): the probability of each cell being in the
    person's view; a hypothesis that runs out keeps its last pose."""
    chances: list[dict[Pos, float]] = []
    for t in range(ticks):
        cells: dict[Pos, float] = {}
        for p, poses in futures:
            if poses:
                pos, facing = poses[min(t, len(poses) - 1)]
                for c in view(layout, pos, facing, angle).cells:
                    cells[c] = cells.get(c, 0.0) + p
        chances.append(cells)
    return chances


def dish_walk(layout: Layout, angle: float, pose: Pose, futures: Sequence[Future], budget: int, price: float,
              garnish: bool, past: tuple[int, int] = (0, 0)) -> tuple[Action, ...]:
    """The best plan from ``pose``: the moves and stays of the walk and the interact that delivers (``garnish``:
    first any stays, then the interact that takes the garnish, then the walk). ``past``: the ticks of this dish
    trip so far in the person's view and in all, the current one included. Empty when no serving counter can be
    reached or there is no prediction."""
    if not layout.serves or not futures:
        return ()
    to_serve = nearest_distances(layout, layout.serves)
    shortest = to_serve.get(pose, UNREACHABLE)
    if shortest >= UNREACHABLE:
        return ()
    budget = max(budget, 0)
    chances = seen_chances(layout, angle, futures, shortest + budget + 2)
    likeliest = max(futures, key=lambda f: f[0])[1]
    person = [likeliest[min(t, len(likeliest) - 1)][0] if likeliest else None for t in range(len(chances))]
    best: tuple[float, int, tuple[Action, ...]] | None = None
    for wait in range(budget + 1) if garnish else range(1):
        # ``frame`` f is the state after f ticks; at a garnish the dish is held from frame wait + 1 on.
        first = wait + 1 if garnish else 0
        prefix = (Action.STAY,) * wait + ((Action.INTERACT,) if garnish else ())
        layer: _Layer = {pose: (chances[wait].get(pose[0], 0.0) if garnish else 0.0, prefix)}
        last = first + shortest + budget - wait
        for frame in range(first, last + 1):
            trip = past[1] + frame - first + (1 if garnish else 0)
            for p, (seen, plan) in layer.items():
                if to_serve.get(p) == 0:
                    extra = frame - first - shortest + wait
                    key = ((past[0] + seen) / max(trip, 1) - price * extra, -extra, plan + (Action.INTERACT,))
                    if best is None or key[:2] > best[:2]:
                        best = key
            if frame < last:
                layer = _step(layout, layer, chances[frame], person[frame], frame + 1, last, to_serve)
    return best[2] if best is not None else ()


def _step(layout: Layout, layer: _Layer, chance: dict[Pos, float], person: Pos | None, frame: int, last: int,
          to_serve: dict[Pose, int]) -> _Layer:
    """Every pose one tick on (a stay or a move), keeping per pose the walk with the most expected ticks in view,
    among those that can still reach the counter by frame ``last``."""
    nxt: _Layer = {}
    successors = tick_successors(layout)
    for p, (seen, plan) in layer.items():
        for action, q in successors[p]:
            if (q[0] != p[0] and q[0] == person) or frame + to_serve.get(q, UNREACHABLE) > last:
                continue
            value = seen + chance.get(q[0], 0.0)
            if q not in nxt or value > nxt[q][0]:
                nxt[q] = (value, plan + (action,))
    return nxt


def walk_seen(layout: Layout, angle: float, pose: Pose, plan: Sequence[Action], poses: Sequence[tuple[Pos, Direction]],
              garnish: bool) -> tuple[int, int]:
    """How a plan of :func:`dish_walk` plays against the person's poses after each tick (the last one held once they
    run out): the ticks of the dish trip the person sees and the trip's ticks, the deliver tick excluded (``garnish``:
    counted from the interact that makes the dish)."""
    holding, seen, ticks = not garnish, 0, 0
    for t, action in enumerate(plan):
        if action is Action.INTERACT:
            if holding:
                break
            holding = True
        elif action.direction is not None:
            pose = next_pose(layout, pose, action.direction)
        if holding and poses:
            here, facing = poses[min(t, len(poses) - 1)]
            ticks += 1
            seen += pose[0] in view(layout, here, facing, angle).cells
    return seen, ticks
