"""The reference's KB gap (planner.summary; docs/domain.md §6): its state info and its per-component rule."""

from __future__ import annotations

from dataclasses import replace

from planner.kb import initial_kb
from planner.layout import parse_layout
from planner.objects import CLEAN_PLATE, ONION
from planner.rules import Rules
from planner.state import initial_state
from planner.summary import StateInfo, kb_diff, kb_diff_trial, state_info, summarize

RULES = Rules()


def test_the_gap_per_component_is_the_references_with_its_rule_for_three():
    # a KB 3 above the world (the garnish believed ready where the board is empty) counts 1 ...
    assert kb_diff("0.2.-1.None", "0.-1.-1.None") == {"grill": 0, "board": 1, "sink": 0, "robot_held": 0}
    # ... the other way round it counts 3; other differences count their size; the robot's hands 0 or 1
    assert kb_diff("0.-1.-1.None", "0.2.-1.None") == {"grill": 0, "board": 3, "sink": 0, "robot_held": 0}
    assert kb_diff("1.0.2.onion", "0.2.0.hot_plate") == {"grill": 1, "board": 2, "sink": 2, "robot_held": 1}


def test_a_trial_gives_the_share_of_ticks_with_a_gap_and_the_means():
    diffs = [kb_diff("0.-1.-1.None", "0.-1.-1.None"), kb_diff("1.-1.-1.None", "0.-1.-1.None"),
             kb_diff("0.-1.-1.None", "0.2.-1.onion"), kb_diff("0.-1.-1.None", "0.-1.-1.None")]
    assert kb_diff_trial(diffs) == (50.0, 2.5, 1.25)
    assert kb_diff_trial(diffs[:1]) == (0.0, None, 0.0)


def test_state_info_of_a_world_and_a_kb():
    layout = parse_layout("XXPXBXX\nX1   2X\nXOMDWSX")
    world = replace(initial_state(layout, RULES), grills=(0,), boards=(1,), sinks=(2,),
                    robot=replace(initial_state(layout, RULES).robot, held=CLEAN_PLATE))
    # the world's grill counts once its steak has cooked a tick; the KB's as soon as a steak is believed there
    assert state_info(world) == StateInfo(0, 1, 2, CLEAN_PLATE)
    kb = replace(initial_kb(world), grills=(0,))
    assert state_info(kb) == StateInfo(1, 1, 2, CLEAN_PLATE)
    assert StateInfo.from_key(state_info(world).key()) == state_info(world)
    assert summarize(world, RULES).to_dict()["reference"] == {"grill": 0, "board": 1, "sink": 2,
                                                              "robot_held": CLEAN_PLATE}


def test_several_boards_reduce_to_the_largest_count_for_the_kb_as_for_the_world():
    layout = parse_layout("XXPXBXBXX\nX1     2X\nXOMDWSXXX")
    world = replace(initial_state(layout, RULES), boards=(None, 2), robot=replace(
        initial_state(layout, RULES).robot, held=ONION))
    assert state_info(world).board == 2
    same = initial_kb(world)
    assert kb_diff(state_info(same), state_info(world)) == dict.fromkeys(("grill", "board", "sink", "robot_held"), 0)
