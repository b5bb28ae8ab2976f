"""The FOV-aware robot's model of the person matches the simulated person it plays with."""

from __future__ import annotations

import numpy as np
import pytest

from planner.events import Event
from planner.human import HumanMemory, HumanModel
from planner.kb import initial_kb, update_kb
from planner.planner_config import PlannerConfig
from planner.qmdp import QmdpRobot
from planner.robots import make_robot
from planner.rules import Rules
from planner.state import initial_state, is_done
from planner.step import step
from study_config import load_layout

RULES = Rules()


@pytest.mark.parametrize("kitchen,seed", [("none_1", 0), ("mid_2", 1), ("side_1", 2)])
def test_modelled_kb_is_the_simulated_humans_kb_every_tick(kitchen, seed):
    """Same FOV, same delay, same worlds: the robot's KB of the person must equal the person's own, from
    the first tick (the world the robot was reset with counts once, as it does for the person)."""
    layout = load_layout(kitchen)
    robot = make_robot("fov_aware", layout, RULES, PlannerConfig())
    assert isinstance(robot, QmdpRobot)
    human_rng, robot_rng = np.random.default_rng(seed).spawn(2)
    world = initial_state(layout, RULES)
    kb, memory = initial_kb(world), HumanMemory()
    events: tuple[Event, ...] = ()
    human = HumanModel(layout, RULES)
    robot.reset(world)
    differing = []
    while not is_done(world, RULES) and world.tick < 120:
        human_action, memory = human.act(world, kb, memory, human_rng)
        decision = robot.decide(world, events, robot_rng)
        if robot.kb != kb:
            differing.append(world.tick)
        world, events = step(layout, world, {"human": human_action, "robot": decision.action}, RULES)
        kb = update_kb(kb, layout, world, angle=120.0, kb_delay=3,
                       own_events=[e for e in events if e.agent == "human"])
    assert world.tick > 20 and differing == []
