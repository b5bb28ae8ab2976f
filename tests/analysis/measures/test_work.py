"""Subtask switches, redundant actions and work shares (analysis.measures.work) on small hand-made tick sequences."""

from __future__ import annotations

import math
from typing import Any

import pytest

from analysis.measures.work import redundant_action_flags, subtask_switch_flags, work_shares


def ctl(subtask: str | None) -> dict[str, Any]:
    return {"subtask": subtask, "last": subtask}


def test_replacing_an_unfinished_subtask_is_a_switch() -> None:
    subtasks = ["pickup_meat", "pickup_meat", "pickup_onion", "pickup_onion"]
    controllers = [ctl("pickup_meat"), ctl("pickup_meat"), ctl("pickup_onion"), ctl("pickup_onion")]
    assert subtask_switch_flags(subtasks, controllers) == [0, 0, 1, 0]


def test_a_new_choice_after_a_finished_or_cancelled_subtask_is_not_a_switch() -> None:
    finished = subtask_switch_flags(["pickup_meat", "drop_meat"], [ctl(None), ctl("drop_meat")])
    cancelled = subtask_switch_flags(["pickup_meat", None, "pickup_onion"],
                                     [ctl(None), ctl(None), ctl("pickup_onion")])
    reselected = subtask_switch_flags(["pickup_meat", "pickup_meat"], [ctl("pickup_meat"), ctl("pickup_meat")])
    assert finished == [0, 0] and cancelled == [0, 0, 0] and reselected == [0, 0]
    assert subtask_switch_flags([], []) == []


def agent(pos: tuple[int, int], facing: str, held: str | None = None) -> dict[str, Any]:
    return {"pos": list(pos), "facing": facing, "held": held}


def world(human: dict[str, Any], robot: dict[str, Any], grills: list[int | None], *,
          boards: list[int | None] | None = None, sinks: list[int | None] | None = None,
          objects: list[dict[str, Any]] | None = None) -> dict[str, Any]:
    return {"human": human, "robot": robot, "grills": grills, "boards": boards or [None], "sinks": sinks or [None],
            "objects": objects or [], "orders_left": 1, "tick": 0, "score": 0}


H, R = (2, 2), (5, 2)


def test_picking_up_meat_for_a_grill_the_robot_filled_is_redundant() -> None:
    start = world(agent(H, "south"), agent(R, "north", "meat"), [None])
    loaded = world(agent(H, "south"), agent(R, "north"), [1])
    picked = world(agent(H, "south", "meat"), agent(R, "north"), [2])
    assert redundant_action_flags(start, [loaded, picked]) == [0, 1]


def test_not_redundant_when_the_human_filled_it_or_a_station_is_free_or_it_happened_in_the_same_step() -> None:
    own = world(agent(H, "south", "meat"), agent(R, "north"), [None])
    assert redundant_action_flags(own, [world(agent(H, "south"), agent(R, "north"), [1]),
                                        world(agent(H, "south", "meat"), agent(R, "north"), [2])]) == [0, 0]
    two_grills = world(agent(H, "south"), agent(R, "north", "meat"), [None, None])
    assert redundant_action_flags(two_grills, [world(agent(H, "south"), agent(R, "north"), [1, None]),
                                               world(agent(H, "south", "meat"), agent(R, "north"), [2, None])]
                                  ) == [0, 0]
    same_step = world(agent(H, "south"), agent(R, "north", "meat"), [None])
    assert redundant_action_flags(same_step, [world(agent(H, "south", "meat"), agent(R, "north"), [1])]) == [0]


def test_a_put_down_on_the_faced_counter_is_not_loading_the_station() -> None:
    start = world(agent(H, "south"), agent(R, "north", "meat"), [1])
    put_down = world(agent(H, "south"), agent(R, "north"), [2], objects=[{"pos": [5, 1], "obj": "meat"}])
    picked = world(agent(H, "south", "meat"), agent(R, "north"), [3], objects=[{"pos": [5, 1], "obj": "meat"}])
    assert redundant_action_flags(start, [put_down, picked]) == [0, 0]


def test_an_emptied_station_forgets_who_loaded_it_and_boards_and_sinks_count_too() -> None:
    start = world(agent(H, "south"), agent(R, "north", "onion"), [None])
    onion_on_board = world(agent(H, "south"), agent(R, "north"), [None], boards=[0])
    picked_onion = world(agent(H, "south", "onion"), agent(R, "north"), [None], boards=[0])
    assert redundant_action_flags(start, [onion_on_board, picked_onion]) == [0, 1]

    plate = world(agent(H, "south"), agent(R, "north", "dirty_plate"), [None])
    in_sink = world(agent(H, "south"), agent(R, "north"), [None], sinks=[0])
    taken = world(agent(H, "south"), agent(R, "north", "clean_plate"), [None], sinks=[None])
    picked_plate = world(agent(H, "south", "dirty_plate"), agent(R, "north", "clean_plate"), [None])
    assert redundant_action_flags(plate, [in_sink, taken, picked_plate]) == [0, 0, 0]


def test_a_station_emptied_and_refilled_in_one_step_belongs_to_the_new_loader() -> None:
    start = world(agent(H, "south", "meat"), agent(R, "north"), [12])
    robot_plated_human_loaded = world(agent(H, "south"), agent(R, "north", "steak_plate"), [1])
    human_picks = world(agent(H, "south", "meat"), agent(R, "north", "steak_plate"), [2])
    assert redundant_action_flags(start, [robot_plated_human_loaded, human_picks]) == [0, 0]


def _events(*pairs: tuple[str, str]) -> list[dict[str, object]]:
    return [{"agent": agent, "kind": kind, "pos": [1, 1], "obj": None} for agent, kind in pairs]


def test_work_shares_count_prep_and_plating_per_agent_and_steps_with_a_collision() -> None:
    steps = [
        _events(("human", "start_cooking"), ("robot", "load_board")),
        _events(("robot", "chop")),
        _events(("robot", "chop"), ("human", "blocked"), ("robot", "blocked")),
        _events(("human", "plate_steak"), ("robot", "dispense")),
        _events(("human", "garnish")),
        _events(("robot", "deliver"), ("human", "blocked")),
        [],
    ]
    shares = work_shares(steps)
    assert shares["human_prep_pct"] == 25.0, "1 of 4 prep events (the meat) was the participant's"
    assert shares["human_plating_pct"] == pytest.approx(200 / 3), "plating and garnish, not the delivery"
    assert shares["collisions"] == 2


def test_work_shares_are_empty_without_kept_events_or_without_such_work() -> None:
    assert all(math.isnan(v) for v in work_shares([None, None]).values())
    shares = work_shares([_events(("human", "pick_up")), None])
    assert math.isnan(shares["human_prep_pct"]) and math.isnan(shares["human_plating_pct"])
    assert shares["collisions"] == 0
