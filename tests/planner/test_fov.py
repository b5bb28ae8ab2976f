"""The FOV rule (docs/domain.md §2): the exact cone plus the two side cells, inclusive edges, 360° sees all."""

from __future__ import annotations

import pytest

from planner.fov import in_view, visible_cells
from planner.geometry import Direction
from planner.layout import parse_layout

# A 9×9 room; the agent stands at the centre (4, 4).
ROOM = parse_layout(
    "XXXXXXXXX\nXOMDPBWSX\nX       X\nX       X\nX   2   X\nX       X\nX      1X\nX       X\nXXXXXXXXX\n",
    name="room")
CENTRE = (4, 4)

# Checked by hand for facing north at 120°: a cell (dx, dy) with dy < 0 is in view when its angle from
# north, atan(|dx| / |dy|), is at most 60°, i.e. |dx| <= 1.732 |dy|; plus the agent's cell and the cells
# directly left and right. '#' = out of view.
NORTH_120 = """\
.........
.........
#.......#
###...###
###...###
#########
#########
#########
#########
"""


def mask_to_cells(mask: str) -> set[tuple[int, int]]:
    return {(x, y) for y, row in enumerate(mask.splitlines()) for x, ch in enumerate(row) if ch == "."}


def rotate(cell: tuple[int, int], quarter_turns: int) -> tuple[int, int]:
    """Rotate a cell about the centre clockwise (north → east → south → west)."""
    x, y = cell[0] - 4, cell[1] - 4
    for _ in range(quarter_turns):
        x, y = -y, x
    return (x + 4, y + 4)


def test_north_120_matches_the_hand_checked_mask():
    assert set(visible_cells(ROOM, CENTRE, Direction.NORTH, 120)) == mask_to_cells(NORTH_120)


@pytest.mark.parametrize(("facing", "turns"), [(Direction.EAST, 1), (Direction.SOUTH, 2), (Direction.WEST, 3)])
def test_other_facings_are_the_same_cone_rotated(facing, turns):
    expected = {rotate(c, turns) for c in mask_to_cells(NORTH_120)}
    assert set(visible_cells(ROOM, CENTRE, facing, 120)) == expected


def test_side_cells_are_in_view_but_the_cell_behind_is_not():
    seen = visible_cells(ROOM, CENTRE, Direction.NORTH, 120)
    assert (3, 4) in seen and (5, 4) in seen and CENTRE in seen
    assert (4, 5) not in seen and (2, 4) not in seen


def test_cone_edge_is_inclusive():
    # (5, 3) is exactly 45° off north: in view at 90°, and (6, 3) at 63.4° is not.
    assert in_view(CENTRE, Direction.NORTH, (5, 3), 90)
    assert not in_view(CENTRE, Direction.NORTH, (6, 3), 90)
    # atan(1/2) = 26.57°: (5, 2) is in a 53.2° cone but not in a 53° one.
    assert in_view(CENTRE, Direction.NORTH, (5, 2), 53.2)
    assert not in_view(CENTRE, Direction.NORTH, (5, 2), 53.0)


def test_360_sees_every_cell():
    assert visible_cells(ROOM, CENTRE, Direction.SOUTH, 360) == frozenset(ROOM.cells())


def test_narrow_view_still_sees_the_sides():
    seen = visible_cells(ROOM, CENTRE, Direction.EAST, 1)
    assert seen == {CENTRE, (4, 3), (4, 5), (5, 4), (6, 4), (7, 4), (8, 4)}


def test_results_are_cached_per_pose():
    first = visible_cells(ROOM, CENTRE, Direction.NORTH, 120)
    assert visible_cells(ROOM, CENTRE, Direction.NORTH, 120) is first
