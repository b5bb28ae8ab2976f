"""Every rule of docs/domain.md §1: the interaction table, collisions, the order of interacts, cooking, orders."""

from __future__ import annotations

from dataclasses import replace

import pytest

from planner.events import Event, EventKind
from planner.geometry import Action, Direction
from planner.layout import Layout
from planner.objects import CLEAN_PLATE, DIRTY_PLATE, DISH, MEAT, ONION, STEAK_PLATE
from planner.rules import Rules
from planner.state import AgentState, WorldState, initial_state, is_done
from planner.step import step

RULES = Rules()
STAY = Action.STAY
# Where the human stands (facing north) to use each station of the test kitchen.
AT = {"onion": (1, 2), "meat": (2, 2), "plate": (3, 2), "grill": (4, 2), "board": (5, 2), "sink": (6, 2),
      "serve": (7, 2)}


def world(kitchen: Layout, held: str | None = None, at: str = "grill", **changes) -> WorldState:
    base = initial_state(kitchen, RULES)
    human = AgentState(AT[at], Direction.NORTH, held)
    return replace(base, human=human, **changes)


def interact(kitchen: Layout, state: WorldState) -> tuple[WorldState, tuple[Event, ...]]:
    return step(kitchen, state, {"human": Action.INTERACT, "robot": STAY}, RULES)


def at_island(kitchen: Layout, held: str | None, on_counter: str | None) -> WorldState:
    """The human at (5, 3) facing west onto the island counter (4, 3)."""
    base = initial_state(kitchen, RULES)
    objects = (((4, 3), on_counter),) if on_counter else ()
    return replace(base, human=AgentState((5, 3), Direction.WEST, held), objects=objects)


def test_put_down_on_empty_counter(kitchen):
    after, events = interact(kitchen, at_island(kitchen, ONION, None))
    assert after.human.held is None and after.object_at((4, 3)) == ONION
    assert events[0].kind is EventKind.PUT_DOWN


def test_pick_up_from_counter(kitchen):
    after, events = interact(kitchen, at_island(kitchen, None, MEAT))
    assert after.human.held == MEAT and after.object_at((4, 3)) is None
    assert events[0].kind is EventKind.PICK_UP


def test_swap_with_counter(kitchen):
    after, events = interact(kitchen, at_island(kitchen, ONION, DIRTY_PLATE))
    assert after.human.held == DIRTY_PLATE and after.object_at((4, 3)) == ONION
    assert events[0].kind is EventKind.SWAP


def test_empty_hand_on_empty_counter_does_nothing(kitchen):
    state = at_island(kitchen, None, None)
    after, events = interact(kitchen, state)
    assert events == () and after.objects == () and after.human == state.human


@pytest.mark.parametrize(("station", "obj"), [("onion", ONION), ("meat", MEAT), ("plate", DIRTY_PLATE)])
def test_dispensers_give_their_object_to_an_empty_hand(kitchen, station, obj):
    after, events = interact(kitchen, world(kitchen, None, station))
    assert after.human.held == obj and events[0].kind is EventKind.DISPENSE


@pytest.mark.parametrize("station", ["onion", "meat", "plate"])
def test_dispensers_ignore_a_full_hand(kitchen, station):
    after, events = interact(kitchen, world(kitchen, MEAT if station != "meat" else ONION, station))
    assert events == () and after.human.held in (MEAT, ONION)


def test_meat_on_empty_grill_starts_cooking_and_counts_this_tick(kitchen):
    after, events = interact(kitchen, world(kitchen, MEAT, "grill"))
    assert after.human.held is None and after.grills == (1,)
    assert events[0].kind is EventKind.START_COOKING


def test_grill_is_ready_after_cook_time_ticks(kitchen):
    state, _ = interact(kitchen, world(kitchen, MEAT, "grill"))
    for _ in range(RULES.cook_time - 2):
        state, _ = step(kitchen, state, {"human": STAY, "robot": STAY}, RULES)
    assert state.grills == (RULES.cook_time - 1,)
    state, _ = step(kitchen, state, {"human": STAY, "robot": STAY}, RULES)
    assert state.grills == (RULES.cook_time,)
    state, _ = step(kitchen, state, {"human": STAY, "robot": STAY}, RULES)
    assert state.grills == (RULES.cook_time,)


def test_clean_plate_takes_a_ready_steak(kitchen):
    after, events = interact(kitchen, world(kitchen, CLEAN_PLATE, "grill", grills=(RULES.cook_time,)))
    assert after.human.held == STEAK_PLATE and after.grills == (None,)
    assert events[0].kind is EventKind.PLATE_STEAK


def test_clean_plate_cannot_take_a_cooking_steak(kitchen):
    after, events = interact(kitchen, world(kitchen, CLEAN_PLATE, "grill", grills=(3,)))
    assert after.human.held == CLEAN_PLATE and after.grills == (4,) and events == ()


def test_more_meat_does_not_speed_up_the_grill(kitchen):
    after, events = interact(kitchen, world(kitchen, MEAT, "grill", grills=(3,)))
    assert after.grills == (4,) and after.human.held == MEAT and events == ()


def test_dirty_plate_into_empty_sink(kitchen):
    after, events = interact(kitchen, world(kitchen, DIRTY_PLATE, "sink"))
    assert after.sinks == (0,) and after.human.held is None and events[0].kind is EventKind.LOAD_SINK


def test_washing_counts_presses_then_gives_a_clean_plate(kitchen):
    state = world(kitchen, None, "sink", sinks=(0,))
    for expected in range(1, RULES.wash_time + 1):
        state, events = interact(kitchen, state)
        assert state.sinks == (expected,) and events[0].kind is EventKind.WASH
    state, events = interact(kitchen, state)
    assert state.human.held == CLEAN_PLATE and state.sinks == (None,)
    assert events[0].kind is EventKind.TAKE_CLEAN_PLATE


def test_onion_onto_empty_board_then_chopping(kitchen):
    state, events = interact(kitchen, world(kitchen, ONION, "board"))
    assert state.boards == (0,) and events[0].kind is EventKind.LOAD_BOARD
    for expected in range(1, RULES.chop_time + 1):
        state, events = interact(kitchen, state)
        assert state.boards == (expected,) and events[0].kind is EventKind.CHOP
    state, events = interact(kitchen, state)
    assert state.boards == (RULES.chop_time,) and events == ()


def test_plated_steak_takes_the_chopped_garnish(kitchen):
    after, events = interact(kitchen, world(kitchen, STEAK_PLATE, "board", boards=(RULES.chop_time,)))
    assert after.human.held == DISH and after.boards == (None,) and events[0].kind is EventKind.GARNISH


def test_plated_steak_cannot_take_an_unchopped_onion(kitchen):
    after, events = interact(kitchen, world(kitchen, STEAK_PLATE, "board", boards=(1,)))
    assert after.human.held == STEAK_PLATE and after.boards == (1,) and events == ()


def test_delivering_a_dish_scores_and_removes_an_order(kitchen):
    after, events = interact(kitchen, world(kitchen, DISH, "serve"))
    assert after.human.held is None and after.orders_left == RULES.orders - 1
    assert after.score == RULES.delivery_reward and events[0].kind is EventKind.DELIVER


@pytest.mark.parametrize(("station", "held"), [("serve", ONION), ("sink", ONION), ("board", MEAT),
                                               ("grill", ONION), ("serve", None)])
def test_anything_else_does_nothing(kitchen, station, held):
    state = world(kitchen, held, station)
    after, events = interact(kitchen, state)
    assert events == () and after.human == state.human and after.score == 0


def test_a_move_into_a_counter_only_turns(kitchen):
    state = replace(initial_state(kitchen, RULES), human=AgentState((5, 3), Direction.SOUTH))
    after, _ = step(kitchen, state, {"human": Action.WEST, "robot": STAY}, RULES)
    assert after.human.pos == (5, 3) and after.human.facing is Direction.WEST


def test_moving_into_the_same_cell_blocks_both_but_both_turn(kitchen):
    state = replace(initial_state(kitchen, RULES), human=AgentState((5, 2), Direction.SOUTH),
                    robot=AgentState((3, 2), Direction.SOUTH))
    after, events = step(kitchen, state, {"human": Action.WEST, "robot": Action.EAST}, RULES)
    assert after.human.pos == (5, 2) and after.robot.pos == (3, 2)
    assert after.human.facing is Direction.WEST and after.robot.facing is Direction.EAST
    assert {e.kind for e in events} == {EventKind.BLOCKED}


def test_swapping_cells_blocks_both(kitchen):
    state = replace(initial_state(kitchen, RULES), human=AgentState((4, 2), Direction.SOUTH),
                    robot=AgentState((3, 2), Direction.SOUTH))
    after, _ = step(kitchen, state, {"human": Action.WEST, "robot": Action.EAST}, RULES)
    assert after.human.pos == (4, 2) and after.robot.pos == (3, 2)


def test_moving_into_a_standing_agent_is_blocked(kitchen):
    state = replace(initial_state(kitchen, RULES), human=AgentState((4, 2), Direction.SOUTH),
                    robot=AgentState((3, 2), Direction.SOUTH))
    after, _ = step(kitchen, state, {"human": Action.WEST, "robot": STAY}, RULES)
    assert after.human.pos == (4, 2) and after.human.facing is Direction.WEST


def test_following_into_a_vacated_cell_is_allowed(kitchen):
    state = replace(initial_state(kitchen, RULES), human=AgentState((4, 2), Direction.SOUTH),
                    robot=AgentState((3, 2), Direction.SOUTH))
    after, _ = step(kitchen, state, {"human": Action.WEST, "robot": Action.WEST}, RULES)
    assert after.human.pos == (3, 2) and after.robot.pos == (2, 2)


def test_interacts_happen_robot_first_then_human(kitchen):
    base = initial_state(kitchen, RULES)
    state = replace(base, robot=AgentState((3, 3), Direction.EAST, ONION),
                    human=AgentState((5, 3), Direction.WEST, None))
    after, events = step(kitchen, state, {"human": Action.INTERACT, "robot": Action.INTERACT}, RULES)
    assert after.robot.held is None and after.human.held == ONION and after.objects == ()
    assert [(e.agent, e.kind) for e in events] == [("robot", EventKind.PUT_DOWN), ("human", EventKind.PICK_UP)]


def test_an_agent_interacting_in_place_blocks_a_move_into_its_cell(kitchen):
    base = initial_state(kitchen, RULES)
    state = replace(base, human=AgentState((2, 2), Direction.NORTH), robot=AgentState((3, 2), Direction.WEST))
    after, _ = step(kitchen, state, {"human": Action.INTERACT, "robot": Action.WEST}, RULES)
    assert after.human.held == MEAT and after.robot.pos == (3, 2)


def test_trial_ends_when_orders_are_done_or_at_the_horizon(kitchen):
    state = initial_state(kitchen, RULES)
    assert not is_done(state, RULES)
    assert is_done(replace(state, orders_left=0), RULES)
    assert is_done(replace(state, tick=RULES.horizon), RULES)


def test_step_is_pure(kitchen):
    state = world(kitchen, MEAT, "grill")
    before = state.to_dict()
    interact(kitchen, state)
    assert state.to_dict() == before
