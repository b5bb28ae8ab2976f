"""The paper's clock on the engine: before each step the task's next step is judged, and one that would do nothing
the participant chose ends the task with its reason while the world stays where it was; steps that walk, work or
come from a key go ahead, and each stored tick says what the cook did (``server.game.steps``)."""

from __future__ import annotations

from dataclasses import replace

from planner.events import Event, EventKind
from planner.geometry import Action, Direction
from planner.kb import KnowledgeBase, initial_kb, update_kb
from planner.layout import Layout, parse_layout
from planner.objects import CLEAN_PLATE, MEAT, STEAK_PLATE
from planner.rules import Rules
from planner.state import AgentState, WorldState, initial_state
from planner.subtasks import Subtask
from server.game.blocked import PATIENCE_STEPS, Reason
from server.game.engine import TickOutcome, TrialEngine
from server.game.steps import NOT_EXECUTABLE
from server.protocol.interrupts import Interrupt
from study_config import load_layout

RULES = Rules(orders=1, horizon=400)
PRACTICE = load_layout("practice")  # board (5,1), sink (7,1), serving hatch (1,3), grill (8,4), meat crate (8,5)
BOARD_SPOT, GRILL_SPOT = (5, 2), (7, 4)
CORRIDOR = parse_layout("XXXXXXXXX\nXOXXXMDPX\nX2 1    X\nXBXXXXWSX\nXXXXXXXXX\n", name="corridor")


def world_with(*, pos=(4, 2), facing=Direction.SOUTH, held=None, grill=None, board=None) -> WorldState:
    world = initial_state(PRACTICE, RULES)
    return replace(world, human=AgentState(pos, facing, held), grills=(grill,), boards=(board,))


def engine_at(world: WorldState, blocked_ticks: int = 5, layout: Layout = PRACTICE) -> TrialEngine:
    kb: KnowledgeBase = update_kb(initial_kb(world), layout, world, angle=360.0, kb_delay=0)
    return TrialEngine(layout, RULES, angle=120.0, kb_delay=1, seed=3, world=world, kb=kb, blocked_ticks=blocked_ticks)


def paper_steps(engine: TrialEngine, most: int) -> tuple[list[TickOutcome], list[str]]:
    """Step as the paper's clock does, at most ``most`` times: ask before each step, stop when the cook has
    nothing to do. Returns the steps taken and the reasons of the refused ones."""
    outcomes: list[TickOutcome] = []
    refused: list[str] = []
    for _ in range(most):
        blocked = engine.refused_step()
        if blocked is not None:
            assert blocked.ended
            refused.append(blocked.reason.code)
        if not engine.controller.has_action():
            break
        outcomes.append(engine.advance(Action.STAY))
    return outcomes, refused


def refusal(engine: TrialEngine, most: int = 10) -> tuple[list[str], Reason | None]:
    """Step as the paper's clock does until the task is refused or ends: the steps taken and the refusal's reason."""
    steps: list[str] = []
    for _ in range(most):
        blocked = engine.refused_step()
        if blocked is not None:
            return steps, blocked.reason
        if not engine.controller.has_action():
            break
        steps.append(engine.advance(Action.STAY).step)
    return steps, None


def test_an_interaction_that_would_do_nothing_is_refused_before_the_world_steps():
    engine = engine_at(world_with(pos=BOARD_SPOT, facing=Direction.NORTH, held=STEAK_PLATE, board=0))
    engine.controller.select(Subtask.PICKUP_GARNISH, STEAK_PLATE)
    before = engine.world
    outcomes, refused = paper_steps(engine, 10)
    assert (outcomes, refused) == ([], ["not_chopped"]), "told at once; on the fixed clock it stood 5 ticks"
    assert engine.world == before and engine.controller.subtask is None


def test_a_cooking_steak_is_waited_for_with_the_stay_key_one_tick_a_press():
    engine = engine_at(world_with(pos=GRILL_SPOT, facing=Direction.EAST, held=CLEAN_PLATE, grill=7))
    engine.controller.select(Subtask.PICKUP_STEAK, CLEAN_PLATE)
    assert paper_steps(engine, 10) == ([], ["steak_cooking"])
    for press in range(1, RULES.cook_time - 7 + 1):
        engine.controller.interrupt(Interrupt.STAY)
        outcomes, _ = paper_steps(engine, 10)
        assert [o.step for o in outcomes] == ["key"], "a press is one step"
        assert engine.world.grills == (7 + press,)
    engine.controller.select(Subtask.PICKUP_STEAK, CLEAN_PLATE)
    outcomes, refused = paper_steps(engine, 10)
    assert refused == [] and [o.step for o in outcomes] == ["work"]
    assert engine.world.human.held == STEAK_PLATE


def test_a_task_with_nothing_known_to_walk_to_is_refused_at_once():
    engine = engine_at(initial_state(PRACTICE, RULES))
    engine.kb = initial_kb(engine.world)
    engine.controller.select(Subtask.PICKUP_CLEAN_PLATE, None)
    assert paper_steps(engine, 10) == ([], ["no_clean_plate"])
    assert engine.tick == 0


def test_walking_and_working_are_never_refused_and_say_what_they_were():
    engine = engine_at(initial_state(PRACTICE, RULES))
    engine.controller.select(Subtask.PICKUP_MEAT, None)
    outcomes, refused = paper_steps(engine, 40)
    assert refused == [] and engine.world.human.held == MEAT
    kinds = [o.step for o in outcomes]
    assert kinds[-1] == "work" and set(kinds[:-1]) == {"walk"}
    assert not any(o.step in NOT_EXECUTABLE for o in outcomes)


def test_a_robot_in_the_only_way_is_waited_for_a_few_steps_then_named():
    engine = engine_at(initial_state(CORRIDOR, RULES), blocked_ticks=50, layout=CORRIDOR)
    engine.controller.select(Subtask.PICKUP_MEAT, None)
    outcomes, refused = paper_steps(engine, 60)
    assert refused == ["robot_in_way"]
    waits = [o for o in outcomes if o.step == "wait"]
    assert 1 <= len(waits) <= PATIENCE_STEPS + 1, "a few steps for the robot to clear the way, not the blocked time"
    assert not any(o.step in NOT_EXECUTABLE for o in outcomes)


def test_the_fixed_clock_steps_regardless_and_the_ticks_say_the_cook_stood():
    engine = engine_at(world_with(pos=BOARD_SPOT, facing=Direction.NORTH, held=STEAK_PLATE, board=0))
    engine.controller.select(Subtask.PICKUP_GARNISH, STEAK_PLATE)
    outcomes = [engine.advance(Action.STAY) for _ in range(7)]
    assert [o.step for o in outcomes] == ["stand"] * 5 + ["idle"] * 2


def test_a_key_is_one_step_even_when_it_changes_nothing():
    engine = engine_at(replace(world_with(pos=(4, 2)), human=AgentState((4, 2), Direction.NORTH, None)))
    engine.controller.interrupt(Interrupt.UP)  # a wall ahead: the cook only faces it
    outcomes, refused = paper_steps(engine, 5)
    assert refused == [] and [o.step for o in outcomes] == ["key"]


GRILL = (8, 4)


def believing(engine: TrialEngine, grills: tuple[int | None, ...]) -> TrialEngine:
    """The participant's knowledge of the grill as it was before the robot's doing (they have not seen it yet)."""
    engine.kb = replace(engine.kb, grills=grills)
    return engine


def test_a_steak_the_robot_took_is_named_as_taken_by_the_robot_not_as_meat_needed():
    # The round: the participant put the steak on; the robot plated it unseen; they come to pick it up.
    engine = believing(engine_at(world_with(pos=GRILL_SPOT, facing=Direction.EAST, held=CLEAN_PLATE)), grills=(10,))
    engine.controller.changes = engine.controller.changes.after(PRACTICE, (
        Event("human", EventKind.START_COOKING, GRILL, MEAT),
        Event("robot", EventKind.PLATE_STEAK, GRILL, CLEAN_PLATE)))
    engine.controller.select(Subtask.PICKUP_STEAK, CLEAN_PLATE)
    assert refusal(engine) == (["look"], Reason("taken_by_robot", "steak", "grill")), \
        "a look at the grill (their knowledge of it is wrong), then the true reason"


def test_a_steak_the_participant_took_themselves_is_simply_not_there():
    engine = believing(engine_at(world_with(pos=GRILL_SPOT, facing=Direction.EAST, held=CLEAN_PLATE)), grills=(10,))
    engine.controller.changes = engine.controller.changes.after(PRACTICE, (
        Event("robot", EventKind.START_COOKING, GRILL, MEAT),
        Event("human", EventKind.PLATE_STEAK, GRILL, CLEAN_PLATE)))
    engine.controller.select(Subtask.PICKUP_STEAK, CLEAN_PLATE)
    assert refusal(engine) == (["look"], Reason("no_steak")), "never 'You need raw meat in your hands'"


def test_a_grill_the_robot_filled_meanwhile_is_named_on_either_clock():
    for paper in (True, False):
        engine = believing(engine_at(world_with(pos=GRILL_SPOT, facing=Direction.EAST, held=MEAT, grill=2),
                                     blocked_ticks=2), grills=(None,))
        engine.controller.changes = engine.controller.changes.after(
            PRACTICE, (Event("robot", EventKind.START_COOKING, GRILL, MEAT),))
        engine.controller.select(Subtask.DROP_MEAT, MEAT)
        if paper:
            told = refusal(engine)[1]
        else:  # the fixed clock steps and tells while the task goes on
            told = next(o.blocked for o in (engine.advance(Action.STAY) for _ in range(3)) if o.blocked).reason
        assert told == Reason("filled_by_robot", MEAT, "grill")


def test_the_robot_taking_a_steak_is_remembered_from_the_world_steps_themselves():
    # The robot plates a ready steak in a real step; the participant's knowledge still has the steak.
    world = world_with(pos=(4, 2), held=CLEAN_PLATE, grill=10)
    world = replace(world, robot=AgentState((7, 4), Direction.EAST, CLEAN_PLATE))
    engine = engine_at(world)
    stale_kb = engine.kb
    engine.advance(Action.INTERACT)
    assert engine.world.grills == (None,) and engine.world.robot.held == STEAK_PLATE
    engine.kb = stale_kb
    engine.world = replace(engine.world, human=AgentState(GRILL_SPOT, Direction.EAST, CLEAN_PLATE),
                           robot=AgentState((6, 5), Direction.SOUTH, STEAK_PLATE))
    engine.controller.select(Subtask.PICKUP_STEAK, CLEAN_PLATE)
    assert refusal(engine)[1] == Reason("taken_by_robot", "steak", "grill")


def test_a_free_grill_the_participant_sees_but_does_not_know_yet_is_looked_at_not_refused():
    # Their knowledge still has the grill busy; they stand facing it, free. "The grill is busy" would be false.
    engine = engine_at(world_with(pos=GRILL_SPOT, facing=Direction.EAST, held=MEAT, grill=None))
    engine.kb = replace(engine.kb, grills=(4,), tracking=None)
    engine.kb_delay = 3
    engine.controller.select(Subtask.DROP_MEAT, MEAT)
    outcomes, refused = paper_steps(engine, 10)
    assert refused == [] and engine.world.grills != (None,), "the meat went on once what they saw had registered"
    assert [o.step for o in outcomes] == ["look"] * 3 + ["work"]
    assert all(o.blocked is None for o in outcomes), "no false notice meanwhile"


def test_an_onion_gone_from_the_counter_is_looked_at_then_fetched_from_the_crate_not_walked_to_again():
    # Their knowledge still has an onion on the counter they face; the robot took it. One look (the study's KB
    # delay), their knowledge catches up, and the task goes on to the onion crate instead of being refused and
    # chosen again at the same empty counter.
    counter = (4, 1)
    engine = engine_at(replace(world_with(), human=AgentState((4, 2), Direction.NORTH, None)))
    engine.kb = replace(engine.kb, objects=((counter, "onion"),), tracking=None)
    engine.controller.changes = engine.controller.changes.after(PRACTICE, (
        Event("robot", EventKind.PICK_UP, counter, "onion"),))
    engine.controller.select(Subtask.PICKUP_ONION, None)
    steps, reason = refusal(engine, 40)
    assert reason is None and engine.world.human.held == "onion"
    assert steps[0] == "look" and steps[-1] == "work" and "stand" not in steps
