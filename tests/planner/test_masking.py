"""What one cook may know of the world at a tick (``planner.masking``): the cells in view with what lies on them and
the stations' status, the other cook only when in view; their own pose and hands and the HUD always; nothing else."""

from __future__ import annotations

from dataclasses import replace

from planner.fov import view
from planner.geometry import Direction
from planner.layout import Terrain
from planner.masking import masked
from planner.objects import MEAT, ONION
from planner.rules import Rules
from planner.state import AgentState, WorldState, initial_state
from study_config import load_layout

KITCHEN = load_layout("practice")  # board (5,1); the robot starts at (2,2)
RULES = Rules()


def world(facing: Direction) -> WorldState:
    base = initial_state(KITCHEN, RULES)
    return replace(base, human=AgentState((4, 2), facing, MEAT), boards=(1,), objects=(((1, 2), ONION),), score=40)


def test_only_what_is_in_view_is_there_and_the_cooks_own_state_always() -> None:
    for facing in Direction:
        w = world(facing)
        seen = view(KITCHEN, (4, 2), facing, 120.0).cells
        mask = masked(KITCHEN, w, RULES, 120.0)
        assert {cell for cell, _ in mask.cells} == set(seen)
        assert (mask.other is not None) == ((2, 2) in seen)
        assert mask.objects == (tuple(w.objects) if (1, 2) in seen else ())
        stations = KITCHEN.boards + KITCHEN.sinks + KITCHEN.grills
        assert {s.pos for s in mask.stations} == {cell for cell in stations if cell in seen}
        assert (mask.me, mask.tick, mask.orders_left, mask.score) == (w.human, w.tick, w.orders_left, 40)


def test_a_station_in_view_shows_its_progress_and_the_robot_sees_from_its_own_pose() -> None:
    w = world(Direction.NORTH)
    board = [s for s in masked(KITCHEN, w, RULES, 360.0).stations if s.kind is Terrain.BOARD]
    assert [(s.pos, s.progress, s.total) for s in board] == [((5, 1), 1, RULES.chop_time)]
    robots = masked(KITCHEN, w, RULES, 360.0, me="robot")
    assert robots.me == w.robot and robots.other == w.human, "at 360° the robot sees the person"
