"""A robot built for a copy of a kitchen (a robot worker unpickles one per trial) plans on the first copy this
process saw, so the planner's caches find their entries by identity instead of comparing two kitchens."""

from __future__ import annotations

import pickle

from planner.interning import interned
from planner.planner_config import PlannerConfig
from planner.robots import make_robot
from planner.rules import Rules
from study_config import load_layout


def test_robots_for_equal_kitchens_share_one_layout_and_rules():
    layout = load_layout("mid_2")
    first = make_robot("fov_aware", pickle.loads(pickle.dumps(layout)), Rules(), PlannerConfig())
    second = make_robot("baseline", pickle.loads(pickle.dumps(layout)), Rules(), PlannerConfig())
    assert first.layout is second.layout and first.rules is second.rules  # type: ignore[attr-defined]
    other = make_robot("fov_aware", load_layout("none_3"), Rules(cook_time=12), PlannerConfig())
    assert other.layout is not first.layout and other.rules.cook_time == 12  # type: ignore[attr-defined]


def test_the_first_equal_instance_is_handed_back_and_unequal_ones_are_kept_apart():
    first, copy = Rules(cook_time=17), Rules(cook_time=17)
    assert first == copy and first is not copy
    assert interned(first) is first and interned(copy) is first
    other = Rules(cook_time=18)
    assert interned(other) is other
