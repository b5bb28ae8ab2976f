"""The field of view: the one function that decides what an agent sees (docs/domain.md §2, paper §III).

A cell is in view of an agent at cell ``p`` facing ``d`` when it is ``p`` itself, one of the two cells
directly left or right of ``p``, or the angle between ``d`` and the vector from ``p``'s centre to the cell's
centre is at most half the FOV angle (inclusive). No range limit and no occlusion (counters are waist
high). An angle of 360° or more sees everything.

Used alike by the participant's browser mask, the simulated human, the robot's model of the human and the
logged metrics. Results are cached per (layout, pose, angle).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

from planner.geometry import Direction, Pos
from planner.layout import Layout, Terrain
from planner.perception import FOV_ANGLE

_EPS = 1e-9
_TRACKED = (Terrain.COUNTER, Terrain.GRILL, Terrain.BOARD, Terrain.SINK)


@dataclass(frozen=True, slots=True)
class View:
    """What one pose sees: every cell in view, and those of them whose contents the KB tracks."""

    cells: frozenset[Pos]
    tracked: tuple[Pos, ...]
    stations: tuple[tuple[Pos, Terrain, int], ...]
    """The grills, boards and sinks in view, with their kind and index."""


def in_view(origin: Pos, facing: Direction, cell: Pos, angle: float) -> bool:
    """The FOV rule for one cell (see the module docstring)."""
    if angle >= 360.0:
        return True
    vx, vy = cell[0] - origin[0], cell[1] - origin[1]
    if vx == 0 and vy == 0:
        return True
    dx, dy = facing.vector
    if abs(vx) + abs(vy) == 1 and vx * dx + vy * dy == 0:
        return True
    return _in_cone(vx, vy, dx, dy, angle)


def in_view_heading(origin: Pos, heading: tuple[float, float], cell: Pos, angle: float) -> bool:
    """:func:`in_view` for a heading that need not be one of the four facings (a unit vector in grid axes, e.g.
    a headset's yaw in the reference's VR logs): the side cells are those of the nearest facing, the cone is
    centred on the heading itself."""
    facing = max(Direction, key=lambda d: d.vector[0] * heading[0] + d.vector[1] * heading[1])
    vx, vy = cell[0] - origin[0], cell[1] - origin[1]
    if angle >= 360.0 or (vx, vy) == (0, 0) or (vx, vy) in facing.sides:
        return True
    return _in_cone(vx, vy, heading[0], heading[1], angle)


def _in_cone(vx: int, vy: int, dx: float, dy: float, angle: float) -> bool:
    dot = vx * dx + vy * dy
    return dot >= math.hypot(vx, vy) * math.hypot(dx, dy) * math.cos(math.radians(angle / 2.0)) - _EPS


def visible_cells(layout: Layout, pos: Pos, facing: Direction, angle: float = FOV_ANGLE) -> frozenset[Pos]:
    """The set of the layout's cells in view from ``pos`` facing ``facing``."""
    return view(layout, pos, facing, angle).cells


def view(layout: Layout, pos: Pos, facing: Direction, angle: float = FOV_ANGLE) -> View:
    """The cached :class:`View` of a pose."""
    table = _table(layout, float(angle))
    key = (pos, facing)
    found = table.get(key)
    if found is None:
        found = table[key] = _compute(layout, pos, facing, float(angle))
    return found


@lru_cache(maxsize=256)
def _table(layout: Layout, angle: float) -> dict[tuple[Pos, Direction], View]:
    return {}


def _compute(layout: Layout, pos: Pos, facing: Direction, angle: float) -> View:
    cells = frozenset(c for c in layout.cells() if in_view(pos, facing, c, angle))
    tracked = tuple(c for c in sorted(cells, key=lambda p: (p[1], p[0]))
                    if c in layout.stations and layout.stations[c][0] in _TRACKED)
    stations = tuple((c, *layout.stations[c]) for c in tracked if layout.stations[c][0] is not Terrain.COUNTER)
    return View(cells, tracked, stations)
