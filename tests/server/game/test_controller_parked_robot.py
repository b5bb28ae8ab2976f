"""The participant's avatar walks around a robot that stays put (a practice robot, a waiting planner).

Regression: the avatar avoided the robot only while it was in view; beside a parked robot that flickered in
and out of view as the avatar turned, it dithered until the horizon (mid_1, mid_2).
"""

from __future__ import annotations

import numpy as np
import pytest

from planner.geometry import Action
from planner.kb import initial_kb, update_kb
from planner.rules import Rules
from planner.state import initial_state
from planner.step import step
from planner.subtasks import Subtask
from server.game.controller import ParticipantController
from study_config import load_layout

ONE_DISH = ("pickup_meat", "drop_meat", "pickup_onion", "drop_onion", "chop_onion", "pickup_plate", "drop_plate",
            "wash_plate", "pickup_clean_plate", "pickup_steak", "pickup_garnish", "deliver_dish")


@pytest.mark.parametrize("kitchen", ["mid_1", "mid_2", "none_3", "side_1", "practice"])
def test_choosing_the_dish_subtasks_one_by_one_delivers_past_a_parked_robot(kitchen):
    layout, rules = load_layout(kitchen), Rules(orders=1)
    world = initial_state(layout, rules)
    kb = initial_kb(world)
    controller = ParticipantController(layout, rules, 120.0)
    rng = np.random.default_rng(0)
    todo = list(ONE_DISH)
    while world.orders_left and world.tick < 200:
        if controller.subtask is None and todo:
            controller.select(Subtask(todo.pop(0)), world.human.held)
        action, _ = controller.decide(world, kb, rng)
        before = world
        world, events = step(layout, world, {"human": action, "robot": Action.STAY}, rules)
        kb = update_kb(kb, layout, world, angle=120, kb_delay=3, own_events=[e for e in events if e.agent == "human"])
        controller.observe(before, world, kb)
    assert world.orders_left == 0, f"{kitchen}: stuck at tick {world.tick} on {controller.subtask}"
