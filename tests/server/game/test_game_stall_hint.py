"""Stall hints (server.game.stall_hint): after ``stall_hint_seconds`` without team progress
the participant gets one hint, phrased from what they know, never naming the robot's planner or condition."""

from __future__ import annotations

from dataclasses import replace

from planner.events import Event, EventKind
from planner.geometry import Direction
from planner.kb import initial_kb
from planner.layout import parse_layout
from planner.registry import PLANNER_NAMES
from planner.rules import Rules
from planner.state import AgentState, initial_state
from server.game.stall_hint import StallWatch, advance, hint_for

RULES = Rules()
# The board (1,2) is used only from (2,2); the sink (5,3) from (5,2), which has other neighbours too.
KITCHEN = parse_layout("""XXXXXXXXXX
XXXOMXXDXX
XB2     1X
XXXPXWXSXX
XXXXXXXXXX
""", name="walkthrough")
START = initial_state(KITCHEN, RULES)


def test_a_hint_comes_once_after_the_quiet_ticks_and_again_only_after_progress():
    state, hints = StallWatch(), []
    world = START
    for _ in range(12):
        world = replace(world, tick=world.tick + 1)
        state, hint = advance(state, KITCHEN, RULES, world, initial_kb(world), (), ticks=5)
        hints.append(hint)
    given = [i for i, h in enumerate(hints) if h is not None]
    assert given == [5], "one hint, once the team potential stood still for 5 ticks"
    world = replace(world, grills=(0,))                       # a steak goes on the grill: progress
    state, hint = advance(state, KITCHEN, RULES, world, initial_kb(world), (), ticks=5)
    assert hint is None and state.quiet == 0
    later = []
    for _ in range(6):
        state, hint = advance(state, KITCHEN, RULES, world, initial_kb(world), (), ticks=5)
        later.append(hint)
    assert [h is not None for h in later] == [False] * 4 + [True, False], "a new quiet stretch hints again"


def test_standing_in_the_only_access_cell_of_the_board_is_said_first():
    world = replace(START, human=AgentState((2, 2), Direction.WEST), boards=(0,))
    load = (Event("human", EventKind.LOAD_BOARD, (1, 2), "onion"),)
    state, _ = advance(StallWatch(), KITCHEN, RULES, world, initial_kb(world), load, ticks=100)
    hint = hint_for(KITCHEN, RULES, world, initial_kb(world), state.loaded_by_you)
    assert (hint.code, hint.text) == ("standing_at_station", "You are standing where the board is used.")
    away = replace(world, human=AgentState((6, 2), Direction.WEST))
    hint = hint_for(KITCHEN, RULES, away, initial_kb(away), state.loaded_by_you)
    assert hint.text == "The onion you put on the board still needs chopping."
    assert hint_for(KITCHEN, RULES, away, initial_kb(away)).text == "The onion on the board still needs chopping."


def test_hints_go_by_what_the_participant_knows_not_by_the_world():
    world = replace(START, human=AgentState((6, 2), Direction.SOUTH, "meat"), sinks=(0,))
    unaware = replace(initial_kb(world), sinks=(None,))        # the participant has not seen the plate in the sink
    assert hint_for(KITCHEN, RULES, world, unaware).text == "You are still holding the meat."
    assert hint_for(KITCHEN, RULES, world, initial_kb(world)).text == "The plate in the sink still needs washing."
    empty = replace(world, human=AgentState((6, 2), Direction.SOUTH))
    assert hint_for(KITCHEN, RULES, empty, replace(initial_kb(empty), sinks=(None,))).code == "look_around"


def test_no_hint_names_the_robot_s_planner_or_a_condition():
    worlds = [replace(START, human=AgentState((2, 2), Direction.WEST), boards=(0,)),
              replace(START, human=AgentState((6, 2), Direction.SOUTH, "dish"), sinks=(1,)),
              replace(START, human=AgentState((3, 2), Direction.SOUTH))]
    for world in worlds:
        text = hint_for(KITCHEN, RULES, world, initial_kb(world)).text.lower()
        assert not any(word in text for word in (*PLANNER_NAMES, "fov", "aware", "baseline", "condition",
                                                 "planner", "robot"))
