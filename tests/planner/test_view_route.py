"""The show walk through the person's view (planner.view_route) in a small hand-made room: the walk after which
the person can acknowledge what the robot holds."""

from __future__ import annotations

from planner.geometry import Action, Direction
from planner.layout import parse_layout
from planner.paths import distance, next_pose
from planner.view_route import show_walk

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


def ticks(actions, start=START):
    """The cells the robot stands on after each tick of a walk (a stay keeps its cell)."""
    pose, cells = start, []
    for action in actions:
        if action.direction is not None:
            pose = next_pose(LAYOUT, pose, action.direction)
        cells.append(pose[0])
    return pose, cells


def extra(actions, start=START):
    pose, _ = ticks(actions, start)
    return len(actions) + distance(LAYOUT, pose, SERVE[0]) - distance(LAYOUT, start, SERVE[0])


def test_a_view_on_the_way_is_walked_through_at_no_cost():
    on_the_way = frozenset({(2, 2), (3, 2), (4, 2)})
    walk_ = show_walk(LAYOUT, START, SERVE, on_the_way, (6, 4), need=3, run=0, detour=6)
    _, cells = ticks(walk_)
    assert Action.STAY not in walk_ and extra(walk_) == 0
    assert cells[-3:] == [(2, 2), (3, 2), (4, 2)]


def test_a_view_off_the_way_is_entered_and_held_for_the_kb_delay():
    walk_ = show_walk(LAYOUT, START, SERVE, SEEN, (6, 4), need=3, run=0, detour=6)
    _, cells = ticks(walk_)
    assert all(c in SEEN for c in cells[-3:])
    assert 0 < extra(walk_) <= 6
    assert show_walk(LAYOUT, START, SERVE, SEEN, (6, 4), need=3, run=0, detour=1) == ()


def test_ticks_already_in_view_count():
    start = ((2, 4), Direction.EAST)
    assert show_walk(LAYOUT, start, SERVE, SEEN, (6, 4), need=3, run=3, detour=6) == ()
    walk_ = show_walk(LAYOUT, start, SERVE, SEEN, (6, 4), need=3, run=2, detour=6)
    _, cells = ticks(walk_, start)
    assert len(walk_) == 1 and cells[0] in SEEN


def test_the_showing_walk_never_enters_the_persons_cell():
    walk_ = show_walk(LAYOUT, START, SERVE, SEEN | {(3, 4)}, (2, 4), need=3, run=0, detour=8)
    _, cells = ticks(walk_)
    assert walk_ and (2, 4) not in cells
