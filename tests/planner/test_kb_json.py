"""The KB rule's memory as JSON (``planner.kb_json``): a KB stored with a tick and read back on resume goes on
exactly as the one that was never stored (docs/domain.md §3)."""

from __future__ import annotations

import json

from planner.geometry import Action
from planner.kb import KnowledgeBase, initial_kb, update_kb
from planner.kb_json import tracking_from_dict, tracking_to_dict
from planner.rules import Rules
from planner.state import WorldState, initial_state
from planner.step import step
from study_config import load_layout

KITCHEN = load_layout("practice")
RULES = Rules()
# the person walks to the onion crate, takes an onion and turns; the robot walks west and back
HUMAN = [Action.EAST, Action.EAST, Action.NORTH, Action.INTERACT, Action.SOUTH, Action.WEST]
ROBOT = [Action.SOUTH, Action.EAST, Action.EAST, Action.STAY, Action.NORTH, Action.WEST]


def played(kb: KnowledgeBase, world: WorldState, ticks: range) -> tuple[KnowledgeBase, WorldState]:
    for t in ticks:
        world, events = step(KITCHEN, world, {"human": HUMAN[t], "robot": ROBOT[t]}, RULES)
        kb = update_kb(kb, KITCHEN, world, angle=120.0, kb_delay=2,
                       own_events=[e for e in events if e.agent == "human"])
    return kb, world


def test_a_kb_read_back_from_json_goes_on_as_the_one_never_stored() -> None:
    start = initial_state(KITCHEN, RULES)
    kb, world = played(initial_kb(start), start, range(3))
    assert kb.tracking is not None
    stored = json.loads(json.dumps(tracking_to_dict(kb.tracking)))
    restored = tracking_from_dict(stored)
    assert restored == kb.tracking
    never_stored, _ = played(kb, world, range(3, 6))
    resumed, _ = played(KnowledgeBase(kb.objects, kb.grills, kb.boards, kb.sinks, kb.robot, restored), world,
                        range(3, 6))
    assert resumed == never_stored
    assert never_stored.tracking is not None and tracking_to_dict(never_stored.tracking) != stored, \
        "the memory moved on: the round trip was not of an empty one"
