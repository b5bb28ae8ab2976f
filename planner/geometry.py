"""Cells, facings and actions of the Steakhouse grid (docs/domain.md §1). The y axis points down."""

from __future__ import annotations

from enum import Enum

Pos = tuple[int, int]


class Direction(str, Enum):
    """A facing. The value is the name used in JSON and on the command line."""

    NORTH = "north"
    SOUTH = "south"
    EAST = "east"
    WEST = "west"

    @property
    def vector(self) -> Pos:
        return _VECTORS[self]

    def ahead(self, pos: Pos) -> Pos:
        dx, dy = _VECTORS[self]
        return (pos[0] + dx, pos[1] + dy)

    @property
    def sides(self) -> tuple[Pos, Pos]:
        """The two unit vectors perpendicular to this facing (left and right of the agent)."""
        dx, dy = _VECTORS[self]
        return ((dy, -dx), (-dy, dx))


_VECTORS: dict[Direction, Pos] = {
    Direction.NORTH: (0, -1),
    Direction.SOUTH: (0, 1),
    Direction.EAST: (1, 0),
    Direction.WEST: (-1, 0),
}

DIRECTIONS: tuple[Direction, ...] = (Direction.NORTH, Direction.SOUTH, Direction.EAST, Direction.WEST)


class Action(str, Enum):
    """The six low-level actions (docs/domain.md §1). A move turns the agent and steps if the target is floor."""

    NORTH = "north"
    SOUTH = "south"
    EAST = "east"
    WEST = "west"
    STAY = "stay"
    INTERACT = "interact"

    @property
    def direction(self) -> Direction | None:
        return _MOVE_DIRECTION.get(self)


_MOVE_DIRECTION: dict[Action, Direction] = {
    Action.NORTH: Direction.NORTH,
    Action.SOUTH: Direction.SOUTH,
    Action.EAST: Direction.EAST,
    Action.WEST: Direction.WEST,
}

ACTIONS: tuple[Action, ...] = tuple(Action)
MOVES: tuple[Action, ...] = (Action.NORTH, Action.SOUTH, Action.EAST, Action.WEST)
MOTIONS: tuple[Action, ...] = MOVES + (Action.STAY,)


def move_action(direction: Direction) -> Action:
    return _MOVE_OF[direction]


_MOVE_OF: dict[Direction, Action] = {d: Action(d.value) for d in DIRECTIONS}


def manhattan(a: Pos, b: Pos) -> int:
    return abs(a[0] - b[0]) + abs(a[1] - b[1])
