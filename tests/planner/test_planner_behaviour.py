"""The exploration of the FOV-aware robot (docs/domain.md §5) in a hand-built situation: a walk through the person's
view is explored, and taken only when the team's progress in the robot's model pays for it.

The robot has just plated a steak out of the human's view; the human last saw it with a clean plate and stands
with a dirty plate. The FOV-aware robot explores the show plan (a step into the person's view, then staying there
until the person could acknowledge the plated steak), but in its model the person carries their plate west to the
sink at once and would not see it, so the rollouts value the direct way more and it goes straight to the board.
The baseline and the no-rollout robot, which explore nothing, go straight too. (The scenes where showing pays:
``test_planner_behaviour_onion.py`` and ``…_island.py``.)
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from planner.fov import visible_cells
from planner.geometry import Action, Direction
from planner.objects import CLEAN_PLATE, DIRTY_PLATE, STEAK_PLATE
from planner.planner_config import PlannerConfig
from planner.robots import make_robot
from planner.rules import Rules
from planner.state import AgentState, initial_state
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


def test_fov_aware_robot_explores_the_way_into_view_and_goes_straight_when_the_person_will_not_see():
    robot, now, decision = first_decision("fov_aware")
    assert decision.explored_kbs >= 2, "the show plan and the direct move were both rolled out"
    assert robot.show.plan(now, robot.kb, ((4, 1),)), "a way into the person's view exists"
    assert decision.action is Action.WEST and not lands_in_view(now, decision.action)
    assert robot.show.pending == ()


def test_baseline_and_no_rollout_robots_go_straight_to_the_board_out_of_view():
    for name in ("baseline", "no_rollout"):
        _, now, decision = first_decision(name)
        assert decision.action is Action.WEST, name
        assert decision.explored_kbs == 0, name
        assert not lands_in_view(now, decision.action), name
