"""The knowledge base (docs/domain.md §3): delayed acknowledgement, persistence, removal, own actions, the robot."""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest

from planner.geometry import Action, Direction
from planner.human import HumanMemory, HumanModel
from planner.kb import KnowledgeBase, initial_kb, update_kb
from planner.objects import MEAT, ONION
from planner.partner import SimulatedPartner
from planner.play import TrialSettings, run_trial
from planner.rules import Rules
from planner.state import AgentState, initial_state
from planner.step import step
from planner.summary import gap_components, kb_gap, kb_gap_components, summarize
from study_config import layout_names, load_layout

RULES = Rules()
ISLAND = (4, 3)
LOOKING = AgentState((4, 4), Direction.NORTH)   # the island counter is straight ahead
AWAY = AgentState((4, 4), Direction.SOUTH)      # the island is behind


def setup(kitchen, objects=(), human=LOOKING, **changes):
    world = replace(initial_state(kitchen, RULES), human=human, objects=objects, **changes)
    return world, initial_kb(replace(world, objects=()))


def tick(kitchen, kb, world, delay=3, events=()):
    return update_kb(kb, kitchen, world, angle=120, kb_delay=delay, own_events=events)


def test_object_is_acknowledged_after_exactly_kb_delay_ticks(kitchen):
    world, kb = setup(kitchen, objects=((ISLAND, ONION),))
    for _ in range(2):
        kb = tick(kitchen, kb, world)
        assert kb.object_at(ISLAND) is None
    kb = tick(kitchen, kb, world)
    assert kb.object_at(ISLAND) == ONION


def test_kb_delay_one_acknowledges_at_once(kitchen):
    world, kb = setup(kitchen, objects=((ISLAND, ONION),))
    assert tick(kitchen, kb, world, delay=1).object_at(ISLAND) == ONION


def test_count_restarts_after_leaving_the_view(kitchen):
    world, kb = setup(kitchen, objects=((ISLAND, ONION),))
    kb = tick(kitchen, kb, world)
    kb = tick(kitchen, kb, world)
    kb = tick(kitchen, kb, replace(world, human=AWAY))
    kb = tick(kitchen, kb, world)
    kb = tick(kitchen, kb, world)
    assert kb.object_at(ISLAND) is None
    kb = tick(kitchen, kb, world)
    assert kb.object_at(ISLAND) == ONION


def test_out_of_view_status_persists(kitchen):
    grill_view = AgentState((4, 2), Direction.NORTH)
    world, kb = setup(kitchen, human=grill_view, grills=(2,))
    for _ in range(3):
        kb = tick(kitchen, kb, world)
    assert kb.grills == (2,)
    world = replace(world, human=replace(grill_view, facing=Direction.SOUTH), grills=(RULES.cook_time,))
    for _ in range(5):
        kb = tick(kitchen, kb, world)
    assert kb.grills == (2,)


def test_status_stays_current_while_in_view(kitchen):
    grill_view = AgentState((4, 2), Direction.NORTH)
    world, kb = setup(kitchen, human=grill_view, grills=(2,))
    for count in range(2, 8):
        kb = tick(kitchen, kb, replace(world, grills=(count,)))
    assert kb.grills == (7,)


def test_missing_object_removed_after_its_place_is_seen_kb_delay_ticks(kitchen):
    world, _ = setup(kitchen)
    kb = replace(initial_kb(world), objects=((ISLAND, MEAT),))
    kb = tick(kitchen, kb, world)
    kb = tick(kitchen, kb, world)
    assert kb.object_at(ISLAND) == MEAT
    kb = tick(kitchen, kb, world)
    assert kb.object_at(ISLAND) is None


def test_own_actions_enter_the_kb_at_once(kitchen):
    world, _ = setup(kitchen, human=AgentState((4, 4), Direction.NORTH, ONION))
    kb = initial_kb(world)
    after, events = step(kitchen, world, {"human": Action.INTERACT, "robot": Action.STAY}, RULES)
    kb = tick(kitchen, kb, after, events=[e for e in events if e.agent == "human"])
    assert kb.object_at(ISLAND) == ONION


def test_robot_held_object_acknowledged_after_delay_and_removed_from_its_old_place(kitchen):
    robot = AgentState((5, 3), Direction.WEST, ONION)   # beside the human's view, holding an onion
    world, _ = setup(kitchen, robot=robot, human=AgentState((4, 4), Direction.EAST))
    far_counter = (0, 2)                                 # behind the human
    kb = replace(initial_kb(world), objects=((far_counter, ONION),), robot=replace(robot, held=None))
    kb = tick(kitchen, kb, world)
    kb = tick(kitchen, kb, world)
    assert kb.robot.held is None and kb.object_at(far_counter) == ONION
    kb = tick(kitchen, kb, world)
    assert kb.robot.held == ONION and kb.robot.pos == (5, 3)
    assert kb.object_at(far_counter) is None


def test_robot_out_of_view_keeps_its_last_acknowledged_pose(kitchen):
    world, _ = setup(kitchen, human=AWAY)
    kb = initial_kb(world)
    moved = replace(world, robot=AgentState((2, 2), Direction.NORTH, MEAT))
    for _ in range(4):
        kb = tick(kitchen, kb, moved)
    assert kb.robot == world.robot


def test_delay_zero_with_360_degrees_is_omniscient():
    for name in layout_names():
        result = run_trial(load_layout(name), seed=7, settings=TrialSettings(angle=360, kb_delay=0))
        assert result.finished
        assert result.kb_gap_mean == 0.0 and result.kb_gap_ticks_pct == 0.0


def test_limited_view_produces_a_gap():
    result = run_trial(load_layout("none_3"), seed=1, settings=TrialSettings(angle=120, kb_delay=3))
    assert result.kb_gap_mean > 0


def test_kb_gap_counts_differing_components(kitchen):
    world, kb = setup(kitchen)
    assert kb_gap(kb, world, RULES) == 0
    world = replace(world, boards=(RULES.chop_time,), robot=replace(world.robot, held=ONION))
    kb = replace(kb, boards=(1,))
    assert kb_gap(kb, world, RULES) == 2


def test_fast_gap_equals_the_gap_of_the_two_summaries():
    layout = load_layout("mid_2")
    world = initial_state(layout, RULES)
    kb = initial_kb(world)
    human, memory, partner = HumanModel(layout, RULES), HumanMemory(), SimulatedPartner(layout, RULES)
    rng = np.random.default_rng(5)
    differing = 0
    for _ in range(150):
        h, memory = human.act(world, kb, memory, rng)
        world, events = step(layout, world, {"human": h, "robot": partner.act(world, (), rng)}, RULES)
        kb = tick(layout, kb, world, events=[e for e in events if e.agent == "human"])
        fast = kb_gap_components(kb, world, RULES)
        assert fast == gap_components(summarize(kb, RULES), summarize(world, RULES))
        differing += sum(fast.values()) > 0
    assert differing > 0


def test_a_kb_read_back_from_json_is_the_same_kb_at_every_tick():
    """Resuming a trial reads the participant's modelled KB back from the store: streaks included."""
    layout = load_layout("mid_2")
    world = initial_state(layout, RULES)
    kb = initial_kb(world)
    human, memory, partner = HumanModel(layout, RULES), HumanMemory(), SimulatedPartner(layout, RULES)
    rng = np.random.default_rng(11)
    with_streaks = 0
    for _ in range(120):
        h, memory = human.act(world, kb, memory, rng)
        world, events = step(layout, world, {"human": h, "robot": partner.act(world, (), rng)}, RULES)
        kb = tick(layout, kb, world, events=[e for e in events if e.agent == "human"])
        assert KnowledgeBase.from_dict(json.loads(json.dumps(kb.to_dict()))) == kb
        with_streaks += bool(kb.streaks)
    assert with_streaks > 0, "the walk must cross ticks with running streaks to test them"


def test_a_stored_kb_naming_an_unknown_object_is_refused(kitchen):
    data = initial_kb(initial_state(kitchen, RULES)).to_dict()
    data["objects"] = [{"pos": [4, 3], "obj": "saucepan"}]
    with pytest.raises(ValueError, match="saucepan"):
        KnowledgeBase.from_dict(data)
