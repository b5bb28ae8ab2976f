"""The robot's model of the person (``planner.person_model``): the person's KB as the robot models it, taken once
per world; whether the person moved; how long they stood in one cell; and when they count as gone (the robot then
plans alone)."""

from __future__ import annotations

from dataclasses import replace

from planner.events import Event, EventKind
from planner.geometry import Direction
from planner.kb import initial_kb
from planner.person_model import PersonModel
from planner.planner_config import PlannerConfig
from planner.rules import Rules
from planner.state import AgentState, WorldState, initial_state
from study_config import load_layout

KITCHEN = load_layout("practice")
RULES = Rules()


def at(world: WorldState, tick: int, pos: tuple[int, int] | None = None,
       facing: Direction | None = None) -> WorldState:
    human = world.human
    return replace(world, tick=tick, human=AgentState(pos or human.pos, facing or human.facing, human.held))


def test_a_restored_kb_is_kept_unless_the_modelled_person_sees_everything() -> None:
    world = initial_state(KITCHEN, RULES)
    restored = replace(initial_kb(world), robot=None)  # stored when the participant had lost track of the robot
    assert restored != initial_kb(world)
    person = PersonModel(KITCHEN, RULES, PlannerConfig())
    person.reset(world, restored)
    assert person.kb is restored
    omniscient = PersonModel(KITCHEN, RULES, PlannerConfig().omniscient_human())
    omniscient.reset(world, restored)
    assert omniscient.kb == initial_kb(world), "a person who sees everything knows the world, not a stored KB"


def test_the_kb_takes_each_world_once() -> None:
    world = initial_state(KITCHEN, RULES)
    person = PersonModel(KITCHEN, RULES, PlannerConfig())
    person.reset(world)
    start = person.kb
    person.observe(world, ())  # the world it was reset with: no new tick
    assert person.kb is start and person.belief is not None
    person.observe(at(world, 1), ())
    assert person.kb is not start


def test_moving_standing_and_doing_nothing_are_told_apart() -> None:
    cfg = replace(PlannerConfig(), alone_ticks=3)
    world = initial_state(KITCHEN, RULES)
    person = PersonModel(KITCHEN, RULES, cfg)
    person.reset(world)
    person.observe(world, ())
    x, y = world.human.pos
    moved = person.observe(at(world, 1, pos=(x + 1, y), facing=Direction.EAST), ())
    assert moved and person.human_still == 0
    turned = person.observe(at(world, 2, pos=(x + 1, y), facing=Direction.NORTH), ())
    assert not turned and person.human_still == 1 and person.partner_still == 0, "turning is a sign of life"
    interact = Event("human", EventKind.LOAD_BOARD, (5, 1))
    person.observe(at(world, 3, pos=(x + 1, y), facing=Direction.NORTH), (interact,))
    assert person.human_still == 2 and person.partner_still == 0, "still in one cell, but working"
    for tick in range(4, 7):
        person.observe(at(world, tick, pos=(x + 1, y), facing=Direction.NORTH), ())
    assert person.partner_still == 3 and person.alone
    person.observe(at(world, 7, pos=(x, y), facing=Direction.WEST), ())
    assert not person.alone and person.human_still == 0
