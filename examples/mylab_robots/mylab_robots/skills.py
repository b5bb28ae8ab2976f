"""The skills both example robots are made of: walk to a kind of station and use it.

Only the robot contract is used (``planner.robot_api``: the kitchen's layout, the world, the six actions). The way
to a set of target cells is a breadth-first search backwards from the poses (cell, facing) that face one of them,
once per kitchen and targets; each tick the robot takes the move that shortens it without stepping into the
person's cell, and interacts once it faces a target.
"""

from __future__ import annotations

from functools import lru_cache

from planner.robot_api import Action, Direction, Layout, Pos, Terrain, WorldState

Pose = tuple[Pos, Direction]
MOVES: dict[Action, Direction] = {Action.NORTH: Direction.NORTH, Action.SOUTH: Direction.SOUTH,
                                  Action.EAST: Direction.EAST, Action.WEST: Direction.WEST}


def cells_of(layout: Layout, kind: Terrain) -> tuple[Pos, ...]:
    return tuple(sorted(pos for pos, (terrain, _) in layout.stations.items() if terrain is kind))


def free_counters(layout: Layout, world: WorldState) -> tuple[Pos, ...]:
    taken = {pos for pos, _ in world.objects}
    return tuple(pos for pos in cells_of(layout, Terrain.COUNTER) if pos not in taken)


def _after(layout: Layout, pose: Pose, action: Action) -> Pose:
    direction = MOVES[action]
    ahead = direction.ahead(pose[0])
    return (ahead if ahead in layout.floor else pose[0], direction)


@lru_cache(maxsize=1024)
def distances(layout: Layout, targets: tuple[Pos, ...]) -> dict[Pose, int]:
    """Moves from each pose to a pose facing one of ``targets`` (absent: none can be reached)."""
    poses = [(cell, d) for cell in layout.floor for d in MOVES.values()]
    before: dict[Pose, list[Pose]] = {}
    for pose in poses:
        for action in MOVES:
            before.setdefault(_after(layout, pose, action), []).append(pose)
    wanted = set(targets)
    dist = {pose: 0 for pose in poses if pose[1].ahead(pose[0]) in wanted}
    frontier = list(dist)
    while frontier:
        nxt = []
        for pose in frontier:
            for prev in before.get(pose, ()):
                if prev not in dist:
                    dist[prev] = dist[pose] + 1
                    nxt.append(prev)
        frontier = nxt
    return dist


def walk(layout: Layout, world: WorldState, targets: tuple[Pos, ...]) -> Action | None:
    """The robot's next action toward using one of ``targets``: ``INTERACT`` when it faces one, else the move that
    brings it closest without stepping into the person's cell (``STAY`` when the person is in the way); ``None``
    when no target can be reached."""
    if not targets:
        return None
    me = world.robot
    pose = (me.pos, me.facing)
    if me.facing.ahead(me.pos) in targets:
        return Action.INTERACT
    table = distances(layout, tuple(sorted(targets)))
    here = table.get(pose)
    if here is None:
        return None
    options = [(table.get(after, here + 1), action) for action in MOVES
               if (after := _after(layout, pose, action))[0] != world.human.pos]
    best = min(options, default=None, key=lambda option: (option[0], option[1].value))
    return best[1] if best is not None and best[0] < here else Action.STAY
