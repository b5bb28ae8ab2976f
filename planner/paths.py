"""Shortest paths over (cell, facing), precomputed per layout (docs/domain.md §4).

Every action costs 1: a move into floor turns and steps; a move into anything else only turns. A target
cell (a station or counter) is reached when the agent stands on a floor cell next to it and faces it; the
interact that follows is not counted here. Distances are computed once per (layout, target) by a backward
breadth-first search and cached.
"""

from __future__ import annotations

from functools import lru_cache

from planner.geometry import DIRECTIONS, MOVES, Action, Direction, Pos, move_action
from planner.layout import Layout

Pose = tuple[Pos, Direction]
UNREACHABLE = 10**6


def next_pose(layout: Layout, pose: Pose, direction: Direction) -> Pose:
    ahead = direction.ahead(pose[0])
    return (ahead if ahead in layout.floor else pose[0], direction)


@lru_cache(maxsize=4096)
def distances_to(layout: Layout, target: Pos) -> dict[Pose, int]:
    """Actions needed from each floor pose to stand next to ``target`` facing it (absent = unreachable)."""
    dist: dict[Pose, int] = {}
    frontier: list[Pose] = []
    for d in DIRECTIONS:
        stand = (target[0] - d.vector[0], target[1] - d.vector[1])
        if stand in layout.floor:
            dist[(stand, d)] = 0
            frontier.append((stand, d))
    preds = _predecessors(layout)
    while frontier:
        nxt: list[Pose] = []
        for pose in frontier:
            for prev in preds.get(pose, ()):
                if prev not in dist:
                    dist[prev] = dist[pose] + 1
                    nxt.append(prev)
        frontier = nxt
    return dist


@lru_cache(maxsize=64)
def _predecessors(layout: Layout) -> dict[Pose, tuple[Pose, ...]]:
    preds: dict[Pose, list[Pose]] = {}
    for cell in layout.floor:
        for facing in DIRECTIONS:
            for d in DIRECTIONS:
                preds.setdefault(next_pose(layout, (cell, facing), d), []).append((cell, facing))
    return {k: tuple(v) for k, v in preds.items()}


def distance(layout: Layout, pose: Pose, target: Pos) -> int:
    return distances_to(layout, target).get(pose, UNREACHABLE)


@lru_cache(maxsize=4096)
def cell_distance(layout: Layout, a: Pos, b: Pos) -> int:
    """Fewest moves from floor cell ``a`` to stand next to and face ``b``, from the best starting facing."""
    table = distances_to(layout, b)
    return min((table.get((a, d), UNREACHABLE) for d in DIRECTIONS), default=UNREACHABLE)


def best_moves(layout: Layout, pose: Pose, target: Pos, blocked: Pos | None = None) -> list[Action]:
    """The moves that bring ``pose`` one step closer to facing ``target``, avoiding the ``blocked`` cell.

    Empty when already there or when every shortening move is blocked.
    """
    return [action for action, cell in _shortening(layout, target).get(pose, ()) if cell != blocked]


@lru_cache(maxsize=4096)
def _shortening(layout: Layout, target: Pos) -> dict[Pose, tuple[tuple[Action, Pos], ...]]:
    """Per pose, the moves (and the cell each ends on) that shorten the way to ``target``."""
    table = distances_to(layout, target)
    result: dict[Pose, tuple[tuple[Action, Pos], ...]] = {}
    for pose, here in table.items():
        result[pose] = tuple((move_action(d), nxt[0]) for d in DIRECTIONS
                             if table.get(nxt := next_pose(layout, pose, d), UNREACHABLE) < here)
    return result


@lru_cache(maxsize=65536)
def detour_moves(layout: Layout, pose: Pose, target: Pos, blocked: Pos) -> tuple[Action, ...]:
    """The first moves of every shortest path to face ``target`` that never enters ``blocked`` (``pose`` is
    not on ``blocked``: it is the other agent's cell)."""
    if distances_to(layout, target).get(pose) == 0:
        return ()
    table = _distances_avoiding(layout, target, blocked)
    here = table.get(pose)
    if here is None:
        return ()
    moves = [move_action(d) for d in DIRECTIONS
             if (after := next_pose(layout, pose, d))[0] != blocked and table.get(after) == here - 1]
    return tuple(sorted(moves, key=lambda a: a.value))


@lru_cache(maxsize=8192)
def _distances_avoiding(layout: Layout, target: Pos, blocked: Pos) -> dict[Pose, int]:
    """:func:`distances_to` over the paths that never enter ``blocked``: one backward search per (target,
    blocked cell) answers every pose, where a search from each pose would repeat it per pose."""
    dist: dict[Pose, int] = {}
    frontier: list[Pose] = []
    for d in DIRECTIONS:
        stand = (target[0] - d.vector[0], target[1] - d.vector[1])
        if stand in layout.floor and stand != blocked:
            dist[(stand, d)] = 0
            frontier.append((stand, d))
    preds = _predecessors(layout)
    while frontier:
        nxt: list[Pose] = []
        for pose in frontier:
            for prev in preds.get(pose, ()):
                if prev not in dist and prev[0] != blocked:
                    dist[prev] = dist[pose] + 1
                    nxt.append(prev)
        frontier = nxt
    return dist


@lru_cache(maxsize=1024)
def nearest_distances(layout: Layout, cells: tuple[Pos, ...]) -> dict[Pose, int]:
    """Per pose, the distance to the nearest of ``cells`` (absent: unreachable)."""
    tables = [distances_to(layout, c) for c in cells]
    keys = set().union(*tables) if tables else set()
    return {pose: min(t.get(pose, UNREACHABLE) for t in tables) for pose in keys}


@lru_cache(maxsize=64)
def tick_successors(layout: Layout) -> dict[Pose, tuple[tuple[Action, Pose], ...]]:
    """Per floor pose, each action of a walk that moves or stays and the pose it leads to: a stay first, so that
    among equally good walks a stay wins over a move that would only turn the agent."""
    return {(cell, facing): ((Action.STAY, (cell, facing)),
                             *((move, next_pose(layout, (cell, facing), move.direction)) for move in MOVES
                               if move.direction is not None))
            for cell in layout.floor for facing in DIRECTIONS}
