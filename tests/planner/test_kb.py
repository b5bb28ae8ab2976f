"""The knowledge base (docs/domain.md §3): delayed acknowledgement, persistence, removal, own actions, the robot."""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest

from planner.fov import visible_cells
from planner.geometry import Action, Direction
from planner.human import HumanMemory, HumanModel
from planner.kb import KnowledgeBase, _contents, initial_kb, update_kb
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


def view_cells(kitchen, pose):
    return visible_cells(kitchen, pose.pos, pose.facing, 120)


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
    """What the person holds is theirs at once, and so is where they put it (the reference's rule tracks the held
    object from the first tick they hold it)."""
    world, _ = setup(kitchen, human=AgentState((4, 4), Direction.NORTH, ONION))
    kb = tick(kitchen, initial_kb(world), world)
    after, events = step(kitchen, world, {"human": Action.INTERACT, "robot": Action.STAY}, RULES)
    kb = tick(kitchen, kb, after, events=[e for e in events if e.agent == "human"])
    assert kb.object_at(ISLAND) == ONION


def test_meat_the_person_puts_on_the_grill_enters_the_kb_at_once(kitchen):
    world, _ = setup(kitchen, human=AgentState((4, 2), Direction.NORTH, MEAT))
    kb = tick(kitchen, initial_kb(world), world)
    after, events = step(kitchen, world, {"human": Action.INTERACT, "robot": Action.STAY}, RULES)
    assert after.grills == (1,)
    kb = tick(kitchen, kb, after, events=[e for e in events if e.agent == "human"])
    assert kb.grills == (1,)


ROBOT_SEEN = AgentState((5, 3), Direction.NORTH)     # beside the island, in view of LOOKING_EAST
LOOKING_EAST = AgentState((4, 4), Direction.EAST)
CRATE_FACING = AgentState((1, 2), Direction.NORTH)   # below the onion crate, behind LOOKING_EAST


def _robot_run(kitchen, poses, delay=3):
    """The KB after each world of ``poses`` (robot states), the person looking east from (4, 4)."""
    world, kb = setup(kitchen, human=LOOKING_EAST)
    kbs = []
    for robot in poses:
        kb = tick(kitchen, kb, replace(world, robot=robot), delay=delay)
        kbs.append(kb)
    return kbs


def test_a_change_of_hands_is_acknowledged_at_once_once_the_robot_was_watched_kb_delay_ticks(kitchen):
    """The robot's count of ticks in view runs on whatever its hands do (the reference's rule): watched for 3
    ticks with empty hands, it is seen taking an onion and the KB knows at that very tick."""
    holding = replace(ROBOT_SEEN, held=ONION)
    kbs = _robot_run(kitchen, [ROBOT_SEEN] * 3 + [holding])
    assert [k.robot.held for k in kbs] == [None, None, None, ONION]
    assert kbs[2].robot.pos == ROBOT_SEEN.pos and kbs[-1].streaks[0][2] == 3


def test_the_robots_count_runs_on_across_a_change_of_hands_and_restarts_out_of_view(kitchen):
    """The robot comes into view holding meat, puts it away after 2 ticks in view and is acknowledged empty-handed
    on its 3rd tick in view (not 3 ticks after the change, as a count per held object would have it). Out of view
    for one tick, its count starts again from 1."""
    meat = replace(ROBOT_SEEN, held=MEAT)
    gone = replace(CRATE_FACING, held=ONION)
    kbs = _robot_run(kitchen, [meat, meat, ROBOT_SEEN, gone, ROBOT_SEEN, ROBOT_SEEN, ROBOT_SEEN])
    assert kbs[0].robot.held is None and kbs[1].robot.held is None  # the start: empty hands, count 1 and 2
    assert kbs[2].robot.held is None and kbs[2].robot.pos == ROBOT_SEEN.pos and kbs[2].streaks[0][2] == 3
    assert kbs[3].robot.pos == ROBOT_SEEN.pos and kbs[3].streaks == ()  # out of view: the last acknowledged pose
    assert [k.streaks[0][2] for k in kbs[4:]] == [1, 2, 3]


def test_a_missing_object_is_forgotten_after_kb_delay_ticks_of_its_place_in_view_not_consecutive(kitchen):
    """An onion the person knew on the island is gone; the KB forgets it once the island has been in view 3
    ticks, however the looks are spread."""
    world, kb = setup(kitchen, objects=((ISLAND, ONION),))
    for _ in range(3):
        kb = tick(kitchen, kb, world)
    assert kb.object_at(ISLAND) == ONION
    kb = tick(kitchen, kb, replace(world, human=AWAY))
    empty = replace(world, objects=())
    for human in (AWAY, LOOKING, AWAY, AWAY, LOOKING, AWAY):
        kb = tick(kitchen, kb, replace(empty, human=human))
        assert kb.object_at(ISLAND) == ONION
    kb = tick(kitchen, kb, empty)
    assert kb.object_at(ISLAND) is None


def test_an_object_the_watched_robot_picks_up_leaves_its_remembered_place(kitchen):
    """The person saw an onion on the island, looked away; the robot, watched for 3 ticks with empty hands, takes
    that onion: the KB no longer places it on the island (its count to be removed starts at the robot's, 3)."""
    world, kb = setup(kitchen, objects=((ISLAND, ONION),), robot=AgentState((5, 3), Direction.WEST))
    for _ in range(3):
        kb = tick(kitchen, kb, world)
    side = AgentState((5, 4), Direction.EAST)  # the robot at (5, 3) beside, the island (4, 3) behind
    assert ISLAND not in view_cells(kitchen, side) and (5, 3) in view_cells(kitchen, side)
    world = replace(world, human=side)
    for _ in range(3):
        kb = tick(kitchen, kb, world)
    assert kb.object_at(ISLAND) == ONION and kb.robot.held is None
    after, _ = step(kitchen, world, {"human": Action.STAY, "robot": Action.INTERACT}, RULES)
    assert after.robot.held == ONION
    kb = tick(kitchen, kb, after)
    assert kb.robot.held == ONION and kb.object_at(ISLAND) is None


def test_an_object_carried_off_out_of_view_is_kept_until_its_place_is_seen(kitchen):
    """The same onion taken by a robot nobody watched stays on the island in the KB until the island is seen."""
    world, kb = setup(kitchen, objects=((ISLAND, ONION),), robot=AgentState((5, 3), Direction.WEST))
    for _ in range(3):
        kb = tick(kitchen, kb, world)
    world = replace(world, human=AWAY)
    kb = tick(kitchen, kb, world)
    after, _ = step(kitchen, world, {"human": Action.STAY, "robot": Action.INTERACT}, RULES)
    for _ in range(3):
        kb = tick(kitchen, kb, after)
        assert kb.object_at(ISLAND) == ONION and kb.robot.held is None
    seen = replace(after, human=LOOKING)
    for _ in range(2):  # the robot back in view: its count and the onion's count to be removed start again
        kb = tick(kitchen, kb, seen)
        assert kb.object_at(ISLAND) == ONION and kb.robot.held is None
    kb = tick(kitchen, kb, seen)
    assert kb.object_at(ISLAND) is None and kb.robot.held == ONION


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


@pytest.mark.parametrize("kitchen_name", ["mid_2", "side_1"])
def test_the_kbs_contents_are_those_of_what_it_believes_at_every_tick(kitchen_name):
    """update_kb keeps the last contents while the believed objects are unchanged (most ticks): they must be the
    contents recomputed from those objects, tick after tick, through interactions, cooking and the view's turns."""
    layout = load_layout(kitchen_name)
    world = initial_state(layout, RULES)
    kb = initial_kb(world)
    human, memory, partner = HumanModel(layout, RULES), HumanMemory(), SimulatedPartner(layout, RULES)
    rng = np.random.default_rng(5)
    kept = changed = 0
    for _ in range(150):
        h, memory = human.act(world, kb, memory, rng)
        world, events = step(layout, world, {"human": h, "robot": partner.act(world, (), rng)}, RULES)
        before = kb
        kb = tick(layout, kb, world, events=[e for e in events if e.agent == "human"])
        assert kb.tracking is not None
        assert kb == _contents(kb.tracking, layout, kb.robot)
        same = before.tracking is not None and before.tracking.believed == kb.tracking.believed
        kept += same
        changed += not same
    assert kept > 0 and changed > 0, "the walk must cross ticks of both kinds"


def test_a_stored_kb_naming_an_unknown_object_is_refused(kitchen):
    data = initial_kb(initial_state(kitchen, RULES)).to_dict()
    data["objects"] = [{"pos": [4, 3], "obj": "saucepan"}]
    with pytest.raises(ValueError, match="saucepan"):
        KnowledgeBase.from_dict(data)
