"""Behaviours the paper reports from the FOV-aware robot (§VI-C), in hand-built situations.

The robot has just plated a steak out of the human's view; the human last saw it with a clean plate.
The FOV-aware robot steps into the human's view and stays there until the human can acknowledge what
it holds (``kb_delay`` ticks), then goes on to the board; the baseline, and the no-rollout robot, which
shares the FOV-aware belief but does not explore, walk straight to the board out of view.

The default FOV-aware robot values nothing but the team's progress (docs/domain.md §5): the show plan wins here
on what the person's knowing does for the team in its rollouts (a person who knows the steak is plated does not go
for a clean plate of their own). The showing robot's hands walk: ``test_planner_behaviour_pickup.py``.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from planner.events import Event
from planner.fov import visible_cells
from planner.geometry import Action, Direction
from planner.objects import CLEAN_PLATE, DIRTY_PLATE, STEAK_PLATE
from planner.planner_config import PlannerConfig
from planner.robots import make_robot
from planner.rules import Rules
from planner.state import AgentState, initial_state
from planner.step import step
from study_config import load_layout

RULES = Rules()
LAYOUT = load_layout("none_3")
HUMAN = AgentState((9, 2), Direction.NORTH, DIRTY_PLATE)
DEFAULT = PlannerConfig()


def situation():
    base = replace(initial_state(LAYOUT, RULES), human=HUMAN, boards=(RULES.chop_time,))
    before = replace(base, robot=AgentState((7, 2), Direction.NORTH, CLEAN_PLATE))
    now = replace(before, robot=AgentState((7, 2), Direction.NORTH, STEAK_PLATE), tick=1)
    return before, now


def first_decision(name: str):
    before, now = situation()
    robot = make_robot(name, LAYOUT, RULES, DEFAULT)
    robot.reset(before)
    return robot, now, robot.decide(now, (), np.random.default_rng(0))


def lands_in_view(world, action: Action) -> bool:
    target = action.direction.ahead(world.robot.pos) if action.direction else world.robot.pos
    return target in visible_cells(LAYOUT, HUMAN.pos, HUMAN.facing, 120)


def test_the_situation_is_out_of_view_and_the_kb_is_stale():
    _, now = situation()
    assert now.robot.pos not in visible_cells(LAYOUT, HUMAN.pos, HUMAN.facing, 120)
    robot, _, _ = first_decision("fov_aware")
    assert robot.kb.robot.held == CLEAN_PLATE


def test_fov_aware_robot_steps_into_view_to_show_the_plated_steak():
    robot, now, decision = first_decision("fov_aware")
    assert lands_in_view(now, decision.action)
    assert decision.explored_kbs >= 2
    assert robot.show.pending == (Action.STAY,) * (3 - 1)


def test_baseline_and_no_rollout_robots_go_straight_to_the_board_out_of_view():
    for name in ("baseline", "no_rollout"):
        _, now, decision = first_decision(name)
        assert decision.action is Action.WEST, name
        assert not lands_in_view(now, decision.action), name


def test_it_stays_until_the_human_can_know_then_goes_on():
    robot, world, decision = first_decision("fov_aware")
    rng = np.random.default_rng(0)
    actions = [decision.action]
    events: tuple[Event, ...] = ()
    for _ in range(6):
        world, events = step(LAYOUT, world, {"human": Action.STAY, "robot": actions[-1]}, RULES)
        actions.append(robot.decide(world, events, rng).action)
        if robot.kb.robot.held == STEAK_PLATE:
            break
    assert robot.kb.robot.held == STEAK_PLATE
    assert actions[1:3] == [Action.STAY, Action.STAY]
    assert actions[-1] is Action.WEST
