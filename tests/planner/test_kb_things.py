"""Which object is which from one tick to the next (``planner.kb_things``), the identities the KB's acknowledgement
rule counts by: an object keeps its identity while it is carried and put down, a station's work makes a new one,
and the identities survive being stored."""

from __future__ import annotations

from planner.geometry import Action
from planner.kb_things import Things, advance, first_things
from planner.rules import Rules
from planner.state import WorldState, initial_state
from planner.step import step
from study_config import load_layout

KITCHEN = load_layout("practice")  # onion crate (6,1), board (5,1)
RULES = Rules()


def play(world: WorldState, things: Things, *moves: Action) -> tuple[WorldState, Things]:
    for move in moves:
        world, events = step(KITCHEN, world, {"human": move, "robot": Action.STAY}, RULES)
        things = advance(things, KITCHEN, world, [e for e in events if e.agent == "human"])
    return world, things


def test_an_onion_keeps_its_identity_while_carried_and_put_down_and_the_board_makes_a_garnish_of_it() -> None:
    world = initial_state(KITCHEN, RULES)
    things = first_things(KITCHEN, world)
    assert things.ordered() == ()
    world, things = play(world, things, Action.EAST, Action.EAST, Action.NORTH, Action.INTERACT)
    assert things.human is not None and things.human.kind == "onion"
    onion = things.human.id
    world, things = play(world, things, Action.WEST, Action.WEST, Action.NORTH, Action.INTERACT)  # onto (4,1)
    assert things.human is None and [(t.id, t.place) for t in things.lying] == [(onion, (4, 1))]
    world, things = play(world, things, Action.INTERACT)
    assert things.human is not None and things.human.id == onion and things.lying == ()
    world, things = play(world, things, Action.EAST, Action.NORTH, Action.INTERACT)  # onto the board (5,1)
    garnish = [t for t in things.lying if t.place == (5, 1)]
    assert [(t.kind, t.state) for t in garnish] == [("garnish", 0)] and garnish[0].id != onion
    world, things = play(world, things, Action.INTERACT, Action.INTERACT)
    assert [(t.id, t.state) for t in things.lying] == [(garnish[0].id, 2)], "chopping works on the same garnish"
    assert Things.from_list(things.to_list()) == things, "stored with the KB and read back"
