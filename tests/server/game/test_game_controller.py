"""The participant's controller: subtasks walk shortest paths judged on the modelled KB, interrupts
override one tick, stop cancels, and a subtask ends when it is done."""

from __future__ import annotations

import numpy as np
import pytest

from planner.geometry import Action, Direction
from planner.kb import initial_kb, update_kb
from planner.paths import distance
from planner.rules import Rules
from planner.state import AgentState, initial_state
from planner.step import step
from planner.subtasks import Subtask
from server.game.controller import QUEUE_LIMIT, ParticipantController
from server.protocol.interrupts import Interrupt

RULES = Rules(orders=1)
RNG = np.random.default_rng(0)


@pytest.fixture
def setup(kitchen):
    world = initial_state(kitchen, RULES)
    return kitchen, world, initial_kb(world), ParticipantController(kitchen, RULES, 120.0)


def test_a_subtask_walks_a_shortest_path_and_ends_when_done(setup):
    layout, world, kb, controller = setup
    controller.select(Subtask.PICKUP_MEAT, None)
    meat = layout.meats[0]
    start = distance(layout, (world.human.pos, world.human.facing), meat)
    for expected_left in range(start - 1, -1, -1):
        action, source = controller.decide(world, kb, RNG)
        assert source == "subtask" and action is not Action.INTERACT
        before = world
        world, events = step(layout, world, {"human": action, "robot": Action.STAY}, RULES)
        assert distance(layout, (world.human.pos, world.human.facing), meat) == expected_left
        assert not controller.observe(before, world, kb)
    action, _ = controller.decide(world, kb, RNG)
    assert action is Action.INTERACT
    before = world
    world, events = step(layout, world, {"human": action, "robot": Action.STAY}, RULES)
    kb = update_kb(kb, layout, world, angle=120.0, kb_delay=1, own_events=events)
    assert world.human.held == "meat"
    assert controller.observe(before, world, kb) and controller.subtask is None
    assert controller.available(world, kb) == (Subtask.DROP_MEAT,)


def test_interrupts_override_one_tick_each_in_order_and_stop_cancels(setup):
    _, world, kb, controller = setup
    controller.select(Subtask.PICKUP_ONION, None)
    assert controller.interrupt(Interrupt.LEFT) and controller.interrupt(Interrupt.INTERACT)
    assert controller.decide(world, kb, RNG) == (Action.WEST, "interrupt")
    assert controller.decide(world, kb, RNG) == (Action.INTERACT, "interrupt")
    assert controller.decide(world, kb, RNG)[1] == "subtask"
    for _ in range(QUEUE_LIMIT):
        assert controller.interrupt(Interrupt.UP)
    assert not controller.interrupt(Interrupt.UP), "a full queue refuses (and changes nothing)"
    assert len(controller.queue) == QUEUE_LIMIT
    assert controller.interrupt(Interrupt.STOP)
    assert controller.subtask is None and not controller.queue and not controller.has_action()
    assert controller.decide(world, kb, RNG) == (Action.STAY, "idle")


def test_selecting_replaces_the_subtask_and_drops_queued_interrupts(setup):
    _, _, _, controller = setup
    controller.select(Subtask.PICKUP_ONION, None)
    controller.interrupt(Interrupt.DOWN)
    controller.select(Subtask.PICKUP_PLATE, None)
    assert controller.subtask is Subtask.PICKUP_PLATE and not controller.queue


def test_targets_come_from_the_modelled_kb_not_the_world(setup):
    layout, world, kb, controller = setup
    counter = (4, 3)  # the island, reachable from both sides
    world = type(world)(**{**{f: getattr(world, f) for f in world.__slots__}, "objects": ((counter, "clean_plate"),)})
    controller.select(Subtask.PICKUP_CLEAN_PLATE, None)
    assert controller.decide(world, kb, RNG) == (Action.STAY, "subtask"), "an unseen plate is no target"
    known = update_kb(kb, layout, world, angle=360.0, kb_delay=0)
    action, _ = controller.decide(world, known, RNG)
    assert action is not Action.STAY


def test_the_robot_is_avoided_only_when_in_view(kitchen):
    world = initial_state(kitchen, RULES)
    human = AgentState((5, 2), Direction.WEST)
    controller = ParticipantController(kitchen, RULES, 120.0)
    controller.select(Subtask.PICKUP_ONION, None)
    kb = initial_kb(world)
    visible = type(world)(**{**{f: getattr(world, f) for f in world.__slots__}, "human": human,
                             "robot": AgentState((4, 2), Direction.EAST)})
    assert controller.decide(visible, kb, RNG)[0] is not Action.WEST
    hidden = type(world)(**{**{f: getattr(world, f) for f in world.__slots__},
                            "human": AgentState((5, 2), Direction.EAST), "robot": AgentState((4, 2), Direction.EAST)})
    assert controller.decide(hidden, kb, RNG)[0] is Action.WEST, "an unseen robot must not bend the path"


def test_round_trip(setup):
    layout, _, _, controller = setup
    controller.select(Subtask.WASH_PLATE, None)
    again = ParticipantController.from_dict(controller.to_dict(), layout, RULES, 120.0)
    assert (again.subtask, again.last) == (Subtask.WASH_PLATE, Subtask.WASH_PLATE)
