"""The dish route through the person's view (planner.view_route) in a small hand-made room."""

from __future__ import annotations

from planner.geometry import Direction
from planner.layout import parse_layout
from planner.paths import distance, next_pose
from planner.view_route import view_route

LAYOUT = parse_layout("\n".join([
    "XXXXXXXX",
    "XMDWPBOX",
    "X1     X",
    "X      X",
    "X     2X",
    "XXXXXSXX",
    "XXXXXXXX",
]), name="route_test")
START = ((1, 2), Direction.EAST)
SERVE = ((5, 5),)
SEEN = frozenset({(1, 4), (2, 4)})
"""A view that holds only the bottom-left cells."""


def walk(actions):
    pose, cells = START, []
    for action in actions:
        assert action.direction is not None
        pose = next_pose(LAYOUT, pose, action.direction)
        cells.append(pose[0])
    return pose, cells


def test_it_passes_the_view_within_the_detour_and_ends_at_the_station():
    shortest = distance(LAYOUT, START, SERVE[0])
    route = view_route(LAYOUT, START, SERVE, SEEN, (6, 4), 4)
    pose, cells = walk(route)
    assert distance(LAYOUT, pose, SERVE[0]) == 0
    assert shortest < len(route) <= shortest + 4
    assert {(1, 4), (2, 4)} <= set(cells)


def test_without_detour_no_walk_passes_that_view():
    assert view_route(LAYOUT, START, SERVE, SEEN, (6, 4), 0) == ()
    assert view_route(LAYOUT, START, SERVE, frozenset(), (6, 4), 4) == ()


def test_it_never_walks_through_the_person():
    route = view_route(LAYOUT, START, SERVE, SEEN | {(3, 4)}, (3, 4), 6)
    _, cells = walk(route)
    assert route and (3, 4) not in cells
