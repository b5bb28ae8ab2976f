"""The lower bound on the robot gap (benchmarks/planner/hands_bound.py): the choice between acknowledging a load and
leaving it unknown, the earliest acknowledgement on a hand-made kitchen, and on played trials a bound that lies
between the lag and the gap as played."""

from __future__ import annotations

import importlib.util
import sys
from dataclasses import replace
from pathlib import Path

import pytest

from planner.geometry import Direction
from planner.layout import parse_layout
from planner.objects import MEAT, ONION
from planner.rules import Rules
from planner.state import AgentState, initial_state

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "benchmarks" / "planner"))
spec = importlib.util.spec_from_file_location("hands_bound", REPO / "benchmarks" / "planner" / "hands_bound.py")
assert spec is not None and spec.loader is not None
hands_bound = importlib.util.module_from_spec(spec)
spec.loader.exec_module(hands_bound)


def test_a_short_load_is_better_left_unknown_than_shown_and_put_down_unseen():
    # empty (right), an onion for 3 ticks acknowledgeable after 2, then empty hands for 10 ticks that could be
    # acknowledged only after 6: showing the onion costs 2 + 6, leaving it unknown 3 + 0
    assert hands_bound.least_wrong([(None, 5, 0), (ONION, 3, 2), (None, 10, 6)]) == 3
    # a long load is worth showing: 2 + 6 against 30
    assert hands_bound.least_wrong([(None, 5, 0), (MEAT, 30, 2), (None, 10, 6)]) == 8
    # a load that cannot be acknowledged is wrong throughout
    assert hands_bound.least_wrong([(MEAT, 4, None)]) == 4


KITCHEN = """\
XOMDPBWSX
X       X
X1     2X
X       X
XXXXXXXXX
"""


def test_the_earliest_acknowledgement_walks_into_the_persons_view_and_waits_for_a_turn():
    layout = parse_layout(KITCHEN, "box")
    rules = Rules()
    start = replace(initial_state(layout, rules), human=AgentState((7, 2), Direction.EAST),
                    robot=AgentState((1, 2), Direction.WEST, MEAT))
    facing_away = [start] * 6
    assert hands_bound.earliest_acknowledgement(layout, facing_away, 0, []) is None  # the robot is behind them
    turned = [start] * 2 + [replace(start, human=AgentState((7, 2), Direction.WEST))] * 4
    assert hands_bound.earliest_acknowledgement(layout, turned, 0, []) == 4  # seen from the third frame on
    # an interact at frame 2 facing the west wall keeps it at (1, 2), still seen from the turn; the hands change
    # at frame 6 (the leg's last anchor): acknowledged at frame 4, within the leg, but not if they change at frame 4
    wall = (0, 2)
    assert hands_bound.earliest_acknowledgement(layout, turned, 0, [(2, wall), (6, wall)]) == 4
    assert hands_bound.earliest_acknowledgement(layout, turned, 0, [(2, wall), (4, wall)]) is None


@pytest.mark.parametrize("robot", ["baseline", "fov_aware"])
def test_on_played_trials_the_bound_lies_between_the_lag_and_the_gap_as_played(robot):
    for seed in range(2):
        _, _, (played, lag, same, *free) = hands_bound.run_one(("none_3", robot, seed))
        assert lag <= same <= played
        assert all(lag <= f <= same for f in free)
        assert free == sorted(free, reverse=True)
