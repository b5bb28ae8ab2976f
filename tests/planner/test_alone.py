"""Working alone (planner.alone): when the partner stops, the robot plans as if it were alone
and finishes every trial one agent can finish with the person standing where they stand."""

from __future__ import annotations

from dataclasses import replace

import pytest

from planner.alone import solo_possible, still_for
from planner.events import Event, EventKind
from planner.geometry import Direction
from planner.layout import Layout
from planner.layout_gen import generate_named
from planner.partner import StillHuman
from planner.planner_config import PlannerConfig
from planner.play import run_trial
from planner.robots import make_robot
from planner.rules import Rules
from planner.state import AgentState, initial_state
from study_config import layout_names, load_layout

RULES = Rules()
SOLO = PlannerConfig(alone_ticks=0)
"""A solo planner: the baseline planning as if alone from the first tick."""


def finishes(layout: Layout, robot: str, config: PlannerConfig = PlannerConfig()) -> bool:
    return run_trial(layout, 0, robot=make_robot(robot, layout, RULES, config),
                     human=StillHuman(layout, RULES)).finished


@pytest.mark.slow
@pytest.mark.parametrize("kitchen", [*layout_names(), *(f"gen:{s}" for s in range(1000, 1006))])
def test_with_a_still_partner_the_fov_aware_robot_finishes_wherever_the_baseline_or_a_solo_planner_does(kitchen):
    layout = generate_named(int(kitchen[4:])) if kitchen.startswith("gen:") else load_layout(kitchen)
    if finishes(layout, "fov_aware"):
        return
    assert not finishes(layout, "baseline"), f"{kitchen} seed 0: the baseline finished, the FOV-aware robot did not"
    assert not finishes(layout, "baseline", SOLO), f"{kitchen} seed 0: a solo planner finished, FOV-aware did not"


def test_only_doing_nothing_counts_as_still():
    person = AgentState((2, 2), Direction.WEST)
    assert still_for(4, person, person, ()) == 5
    assert still_for(4, person, replace(person, facing=Direction.NORTH), ()) == 0, "turning is doing something"
    assert still_for(4, person, person, (Event("human", EventKind.BLOCKED, (1, 2)),)) == 0, "so is trying to move"
    assert still_for(4, person, person, (Event("robot", EventKind.CHOP, (1, 2)),)) == 5


def test_one_agent_cannot_finish_where_the_person_stands_on_the_only_way_to_a_station():
    # gen_1003_peninsula: the sink (1,9) is used only from the person's start cell (1,8).
    layout = generate_named(1003)
    world = initial_state(layout, RULES)
    assert not solo_possible(layout, world)
    assert solo_possible(layout, replace(world, human=AgentState((5, 5), Direction.SOUTH)))
