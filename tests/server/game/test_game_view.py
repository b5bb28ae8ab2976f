"""Masking as a property of any world and pose: exactly the cells in view, their contents, and the robot
only when its cell is in view (``planner.fov.view`` is the one visibility function)."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from planner.fov import view
from planner.geometry import DIRECTIONS
from planner.objects import OBJECTS
from planner.rules import Rules
from planner.state import AgentState, WorldState
from planner.vocabulary import TERRAIN_NAMES
from server.game.view import visible_world
from study_config import load_layout

LAYOUT = load_layout("mid_2")
FLOOR = sorted(LAYOUT.floor)
RULES = Rules()


@st.composite
def worlds(draw):
    human, robot = draw(st.lists(st.sampled_from(FLOOR), min_size=2, max_size=2, unique=True))
    counters = draw(st.lists(st.sampled_from(LAYOUT.counters), unique=True, max_size=12))
    status = st.one_of(st.none(), st.integers(0, 12))
    return WorldState(
        human=AgentState(human, draw(st.sampled_from(DIRECTIONS)), draw(st.sampled_from((None, *OBJECTS)))),
        robot=AgentState(robot, draw(st.sampled_from(DIRECTIONS)), draw(st.sampled_from((None, *OBJECTS)))),
        objects=tuple(sorted((c, draw(st.sampled_from(OBJECTS))) for c in counters)),
        grills=tuple(draw(status) for _ in LAYOUT.grills), boards=tuple(draw(status) for _ in LAYOUT.boards),
        sinks=tuple(draw(status) for _ in LAYOUT.sinks), orders_left=2)


@settings(max_examples=200, deadline=None)
@given(world=worlds(), angle=st.sampled_from([60.0, 90.0, 120.0, 180.0, 360.0]))
def test_exactly_the_visible_part_of_the_world_is_sent(world, angle):
    cells, robot = visible_world(LAYOUT, world, RULES, angle)
    seen = view(LAYOUT, world.human.pos, world.human.facing, angle).cells
    assert {(c.x, c.y) for c in cells} == seen
    objects = dict(world.objects)
    for cell in cells:
        pos = (cell.x, cell.y)
        assert cell.terrain == TERRAIN_NAMES[LAYOUT.terrain(pos)]
        assert cell.object == objects.get(pos)
        assert (cell.station is not None) == (cell.terrain in ("grill", "board", "sink"))
    assert (robot is not None) == (world.robot.pos in seen)
    if robot is not None:
        assert (robot.x, robot.y, robot.held) == (*world.robot.pos, world.robot.held)
