"""The hands walk: the robot's way to its next station planned so that the person comes to know what it holds
(behaviour 1, and the robot gap), on the person's predicted views (docs/domain.md §5, "The showing robot").

While the modelled KB is wrong about the robot's hands (a load the person has not acknowledged, or empty hands
after a put-down they did not see), the robot takes, among all walks to a cell facing one of ``cells`` at most
``budget`` ticks longer than the shortest (stays included, so waiting in view, at the station too, is one such
walk), the one with the fewest expected ticks at which the person's KB is still wrong about its hands, plus
``price`` per extra tick. The person acknowledges the robot's hands at the tick it has stood ``need`` consecutive
ticks in their view (docs/domain.md §3); their view at each coming tick is predicted, one sequence of poses per
hypothesis of what they are doing, weighted by its probability (:meth:`planner.qmdp.QmdpRobot.predicted_worlds`).
Unlike the dish walk's expected share (:mod:`planner.dish_walk`), an acknowledgement needs consecutive ticks
under one hypothesis, so the programme keeps each hypothesis's streak: a pure dynamic programme over (tick, pose,
streaks), the walk never stepping into the cell where the most likely hypothesis puts the person at that tick.
"""

from __future__ import annotations

from collections.abc import Sequence

from planner.dish_walk import Future
from planner.fov import view
from planner.geometry import Action, Pos
from planner.layout import Layout
from planner.paths import UNREACHABLE, Pose, nearest_distances, tick_successors

_State = tuple[Pose, tuple[int, ...]]
_Layer = dict[_State, tuple[float, tuple[Action, ...]]]


def hands_walk(layout: Layout, angle: float, pose: Pose, cells: tuple[Pos, ...], futures: Sequence[Future],
               need: int, run: int, budget: int, price: float) -> tuple[Action, ...]:
    """The best walk from ``pose`` to stand facing one of ``cells``: its moves and stays, without the interact
    that follows. ``futures``: the hypotheses of the person's poses (weights need not sum to 1); ``need``: the
    consecutive ticks in view that make the person acknowledge the robot's hands (the KB delay); ``run``: the
    ticks the robot has already stood in the person's view holding what it holds now (its streak in the modelled
    KB); ``budget``: the most extra ticks over the shortest way; ``price``: what an extra tick costs, in expected
    ticks of the person's KB being wrong. Empty when the robot already stands there, none of ``cells`` can be
    reached or there is no prediction."""
    to_target = nearest_distances(layout, cells)
    shortest = to_target.get(pose, UNREACHABLE)
    if not futures or shortest == 0 or shortest >= UNREACHABLE:
        return ()
    last = shortest + max(budget, 0)
    total = sum(weight for weight, _ in futures) or 1.0
    merged: dict[tuple[frozenset[Pos], ...], float] = {}  # hypotheses with the same views are one
    for weight, poses in futures:
        seen = tuple(view(layout, *poses[min(t, len(poses) - 1)], angle).cells if poses else frozenset()
                     for t in range(last))
        merged[seen] = merged.get(seen, 0.0) + weight / total
    views, weights = list(merged), list(merged.values())
    likeliest = max(futures, key=lambda f: f[0])[1]
    person = [likeliest[min(t, len(likeliest) - 1)][0] if likeliest else None for t in range(last)]
    successors = tick_successors(layout)
    layer: _Layer = {(pose, tuple(min(run, need) for _ in views)): (0.0, ())}
    best: tuple[float, int, tuple[Action, ...], Pose] | None = None
    for frame in range(last + 1):
        for (p, streaks), (cost, plan) in layer.items():
            if frame and (to_target.get(p) == 0 or min(streaks) >= need):
                # Arrived, or known under every hypothesis: the rest is the shortest way, at no further cost.
                extra = frame + to_target[p] - shortest
                if best is None or (cost + price * extra, extra) < best[:2]:
                    best = (cost + price * extra, extra, plan, p)
        if frame == last:
            break
        nxt: _Layer = {}
        for (p, streaks), (cost, plan) in layer.items():
            if min(streaks) >= need:
                continue
            for action, q in successors[p]:
                if (q[0] != p[0] and q[0] == person[frame]) or frame + 1 + to_target.get(q, UNREACHABLE) > last:
                    continue
                after = tuple(need if s >= need else (s + 1 if q[0] in views[h][frame] else 0)
                              for h, s in enumerate(streaks))
                wrong = cost + sum(w for w, s in zip(weights, after, strict=True) if s < need)
                if (q, after) not in nxt or wrong < nxt[(q, after)][0]:
                    nxt[(q, after)] = (wrong, plan + (action,))
        layer = nxt
    return best[2] + _shortest_way(layout, best[3], to_target) if best is not None else ()


def _shortest_way(layout: Layout, pose: Pose, to_target: dict[Pose, int]) -> tuple[Action, ...]:
    """A shortest way from ``pose`` to the target of ``to_target``."""
    way: list[Action] = []
    while to_target[pose]:
        action, pose = next((a, q) for a, q in tick_successors(layout)[pose]
                            if to_target.get(q, UNREACHABLE) == to_target[pose] - 1)
        way.append(action)
    return tuple(way)
