"""A choice that cannot work is explained, never silent: subtasks that do not fit what the cook holds are
refused with the reason, an interaction that does nothing is named from the faced cell, and a subtask that makes
no progress ends itself after the study's blocked time (no deadlock). Checked on the engine, without a browser."""

from __future__ import annotations

from dataclasses import replace

import pytest

from planner.geometry import Action, Direction
from planner.kb import KnowledgeBase, initial_kb, update_kb
from planner.layout import parse_layout
from planner.objects import CLEAN_PLATE, DIRTY_PLATE, DISH, MEAT, OBJECTS, ONION, STEAK_PLATE
from planner.rules import Rules
from planner.state import AgentState, WorldState, initial_state
from planner.subtasks import SUBTASKS, Subtask
from server.game.blocked import NOTICE_AFTER_MOVES, Reason, hands_reason, interaction_reason
from server.game.engine import TickOutcome, TrialEngine
from server.game.needs import NEEDS, hands_fit
from study_config import load_layout

RULES = Rules(orders=1, horizon=400)
PRACTICE = load_layout("practice")  # board (5,1), sink (7,1), serving hatch (1,3), grill (8,4), meat crate (8,5)
BOARD_SPOT, SINK_SPOT, GRILL_SPOT, SERVE_SPOT = (5, 2), (7, 2), (7, 4), (2, 3)


def world_with(layout=PRACTICE, *, pos=(4, 2), facing=Direction.SOUTH, held=None, grill=None, board=None,
               sink=None, robot=None) -> WorldState:
    world = initial_state(layout, RULES)
    world = replace(world, human=AgentState(pos, facing, held), grills=(grill,), boards=(board,), sinks=(sink,))
    return world if robot is None else replace(world, robot=robot)


def seen_everything(layout, world: WorldState) -> KnowledgeBase:
    return update_kb(initial_kb(world), layout, world, angle=360.0, kb_delay=0)


@pytest.mark.parametrize("subtask", SUBTASKS)
@pytest.mark.parametrize("held", [None, *OBJECTS])
def test_a_subtask_fits_exactly_what_its_table_says_and_otherwise_names_why(subtask, held):
    need = NEEDS[subtask]
    fits = held is None if need == "nothing" else (held is not None if need == "something" else held == need)
    assert hands_fit(subtask, held) is fits
    reason = hands_reason(subtask, held)
    if fits:
        assert reason is None
    elif need == "nothing":
        assert reason == Reason("hands_full", held)
    elif need == "something":
        assert reason == Reason("hands_empty")
    else:
        assert reason == Reason("needs_item", need)


def test_the_hands_table_is_the_forced_continuation_of_each_object():
    assert {NEEDS[s] for s in (Subtask.PICKUP_STEAK, Subtask.PICKUP_GARNISH, Subtask.DELIVER_DISH)} == {
        CLEAN_PLATE, STEAK_PLATE, DISH}
    assert (NEEDS[Subtask.DROP_MEAT], NEEDS[Subtask.DROP_ONION], NEEDS[Subtask.DROP_PLATE]) == (
        MEAT, ONION, DIRTY_PLATE)


@pytest.mark.parametrize(("spot", "facing", "held", "station", "expected"), [
    (BOARD_SPOT, Direction.NORTH, STEAK_PLATE, {"board": 0}, Reason("not_chopped")),
    (BOARD_SPOT, Direction.NORTH, STEAK_PLATE, {"board": None}, Reason("no_garnish")),
    (BOARD_SPOT, Direction.NORTH, STEAK_PLATE, {"board": 2}, None),
    (BOARD_SPOT, Direction.NORTH, ONION, {"board": 1}, Reason("board_busy")),
    (BOARD_SPOT, Direction.NORTH, None, {"board": None}, Reason("nothing_to_chop")),
    (BOARD_SPOT, Direction.NORTH, None, {"board": 2}, Reason("already_chopped")),
    (BOARD_SPOT, Direction.NORTH, None, {"board": 1}, None),
    (BOARD_SPOT, Direction.NORTH, MEAT, {"board": None}, Reason("needs_item", ONION)),
    (GRILL_SPOT, Direction.EAST, CLEAN_PLATE, {"grill": 4}, Reason("steak_cooking")),
    (GRILL_SPOT, Direction.EAST, CLEAN_PLATE, {"grill": None}, Reason("no_steak")),
    (GRILL_SPOT, Direction.EAST, CLEAN_PLATE, {"grill": 10}, None),
    (GRILL_SPOT, Direction.EAST, MEAT, {"grill": 3}, Reason("grill_busy")),
    (GRILL_SPOT, Direction.EAST, None, {"grill": 10}, Reason("needs_item", CLEAN_PLATE)),
    (SINK_SPOT, Direction.NORTH, DIRTY_PLATE, {"sink": 0}, Reason("sink_busy")),
    (SINK_SPOT, Direction.NORTH, None, {"sink": None}, Reason("nothing_to_wash")),
    (SINK_SPOT, Direction.NORTH, ONION, {"sink": 2}, Reason("hands_full", ONION)),
    (SINK_SPOT, Direction.NORTH, None, {"sink": 1}, None),
    (SERVE_SPOT, Direction.WEST, STEAK_PLATE, {}, Reason("needs_item", DISH)),
    (SERVE_SPOT, Direction.WEST, DISH, {}, None),
    ((6, 2), Direction.NORTH, MEAT, {}, Reason("hands_full", MEAT)),  # the onion crate
    ((4, 2), Direction.SOUTH, None, {}, Reason("nothing_there")),      # floor ahead
])
def test_an_interaction_that_would_do_nothing_is_named_from_the_faced_cell(spot, facing, held, station, expected):
    world = world_with(pos=spot, facing=facing, held=held, **station)
    assert interaction_reason(PRACTICE, world, RULES) == expected


def engine_at(world: WorldState, blocked_ticks: int = 5, layout=PRACTICE) -> TrialEngine:
    return TrialEngine(layout, RULES, angle=120.0, kb_delay=1, seed=3, world=world, kb=seen_everything(layout, world),
                       blocked_ticks=blocked_ticks)


def run(engine: TrialEngine, ticks: int) -> list[TickOutcome]:
    return [engine.advance(Action.STAY) for _ in range(ticks)]


def test_a_plated_steak_at_an_unchopped_onion_ends_itself_with_the_reason_instead_of_waiting_all_round():
    engine = engine_at(world_with(pos=BOARD_SPOT, facing=Direction.NORTH, held=STEAK_PLATE, board=0), blocked_ticks=5)
    assert engine.controller.select(Subtask.PICKUP_GARNISH, STEAK_PLATE) is None
    outcomes = run(engine, 8)
    blocked = [(o.tick, o.blocked.reason.code, o.blocked.ended) for o in outcomes if o.blocked]
    assert blocked == [(1, "not_chopped", False), (5, "not_chopped", True)], "told once at once, ended after 5"
    assert engine.controller.subtask is None
    assert [o.source for o in outcomes] == ["subtask"] * 5 + ["idle"] * 3
    assert engine.world.human.held == STEAK_PLATE, "nothing was lost"


def test_waiting_for_a_cooking_steak_is_progress_so_the_subtask_goes_on_and_succeeds():
    engine = engine_at(world_with(pos=GRILL_SPOT, facing=Direction.EAST, held=CLEAN_PLATE, grill=3), blocked_ticks=3)
    engine.controller.select(Subtask.PICKUP_STEAK, CLEAN_PLATE)
    outcomes = run(engine, 9)
    notices = [(o.blocked.reason.code, o.blocked.ended) for o in outcomes if o.blocked]
    assert notices == [("steak_cooking", False)], "the cook is told once why it waits, and the wait is not cut short"
    assert engine.world.human.held == STEAK_PLATE and any(o.subtask_finished for o in outcomes)


def test_a_subtask_with_nothing_known_to_walk_to_says_so_and_ends():
    engine = engine_at(initial_state(PRACTICE, RULES), blocked_ticks=4)
    engine.kb = initial_kb(engine.world)
    engine.controller.select(Subtask.PICKUP_CLEAN_PLATE, None)
    outcomes = run(engine, 4)
    assert [(o.blocked.reason.code, o.blocked.ended) for o in outcomes if o.blocked] == [
        ("no_clean_plate", False), ("no_clean_plate", True)]


@pytest.mark.parametrize(("subtask", "station", "expected"), [
    (Subtask.CHOP_ONION, {"board": None}, "nothing_to_chop"),
    (Subtask.CHOP_ONION, {"board": 2}, "already_chopped"),
    (Subtask.WASH_PLATE, {"sink": None}, "nothing_to_wash"),
    (Subtask.WASH_PLATE, {"sink": 2}, "already_washed"),
])
def test_chopping_or_washing_with_nothing_waiting_ends_at_once_and_says_why(subtask, station, expected):
    engine = engine_at(world_with(**station))
    engine.controller.select(subtask, None)
    (first,) = run(engine, 1)
    assert first.subtask_finished and first.blocked is not None
    assert (first.blocked.reason.code, first.blocked.ended) == (expected, True)


def test_chopping_that_did_its_work_ends_quietly():
    engine = engine_at(world_with(pos=BOARD_SPOT, facing=Direction.NORTH, board=0))
    engine.controller.select(Subtask.CHOP_ONION, None)
    outcomes = run(engine, 2)
    assert outcomes[-1].subtask_finished and engine.world.boards == (2,)
    assert all(o.blocked is None for o in outcomes)


def test_putting_meat_on_a_grill_known_to_be_busy_names_the_grill():
    engine = engine_at(world_with(held=MEAT, grill=3), blocked_ticks=2)
    engine.controller.select(Subtask.DROP_MEAT, MEAT)
    outcomes = run(engine, 2)
    assert [(o.blocked.reason.code, o.blocked.ended) for o in outcomes if o.blocked] == [
        ("grill_busy", False), ("grill_busy", True)]


def test_a_choice_that_does_not_fit_the_hands_is_refused_and_changes_nothing():
    engine = engine_at(initial_state(PRACTICE, RULES))
    engine.controller.select(Subtask.PICKUP_ONION, None)
    refused = engine.controller.select(Subtask.DELIVER_DISH, None)
    assert refused is not None and refused.ended and refused.reason == Reason("needs_item", DISH)
    assert engine.controller.subtask is Subtask.PICKUP_ONION


CORRIDOR = parse_layout("XXXXXXXXX\nXOXXXMDPX\nX2 1    X\nXBXXXXWSX\nXXXXXXXXX\n", name="corridor")


def test_a_robot_blocking_the_only_way_is_named_once_seen_and_the_subtask_ends():
    world = initial_state(CORRIDOR, RULES)
    engine = engine_at(world, blocked_ticks=6, layout=CORRIDOR)
    engine.controller.select(Subtask.PICKUP_MEAT, None)
    outcomes = run(engine, 12)
    blocked = [(o.blocked.reason.code, o.blocked.ended) for o in outcomes if o.blocked]
    assert blocked == [("robot_in_way", False), ("robot_in_way", True)]
    told = next(o for o in outcomes if o.blocked)
    assert told.robot_in_fov, "the robot is named only when the participant can see it"
    stalled = [o for o in outcomes[: outcomes.index(told) + 1] if o.human_action is Action.STAY]
    assert len(stalled) >= NOTICE_AFTER_MOVES
    assert engine.controller.subtask is None and engine.world.robot.pos == (3, 2)


def test_an_interact_key_that_does_nothing_says_why_and_one_that_works_says_nothing():
    from server.protocol.interrupts import Interrupt

    engine = engine_at(world_with(pos=SINK_SPOT, facing=Direction.NORTH, held=None, sink=None))
    assert engine.controller.interrupt(Interrupt.INTERACT)
    [outcome] = run(engine, 1)
    assert outcome.source == "interrupt" and outcome.blocked is not None
    assert (outcome.blocked.subtask, outcome.blocked.reason, outcome.blocked.ended) == (
        None, Reason("nothing_to_wash"), False)
    assert run(engine, 1)[0].blocked is None, "a step without a key says nothing"
    engine = engine_at(world_with(pos=(7, 5), facing=Direction.EAST, held=None))  # facing the meat crate
    assert engine.controller.interrupt(Interrupt.INTERACT)
    [took] = run(engine, 1)
    assert took.world.human.held == MEAT and took.blocked is None
