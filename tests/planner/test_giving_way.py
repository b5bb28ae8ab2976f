"""The decision's giving-way part (:mod:`planner.giving_way`): it answers an action or the options, and the robot's
new stance, keeping nothing of its own. The full scenes (standoffs, cycles, visits) are ``test_standoff.py`` and
``test_cycle.py``; here the part itself, on hand-made stances."""

from __future__ import annotations

from dataclasses import replace

from planner.cycle import CycleWatch
from planner.flicker import FlickerWatch
from planner.geometry import Action, Direction
from planner.giving_way import GivingWay, Stance
from planner.kb import initial_kb
from planner.moment import Moment
from planner.planner_config import PlannerConfig
from planner.rollout import RobotTasker, Rollout
from planner.rules import Rules
from planner.standoff import Standoff
from planner.state import AgentState, initial_state
from planner.subtasks import Subtask
from study_config import load_layout

RULES = Rules()
LAYOUT = load_layout("none_3")
CONFIG = PlannerConfig()
WAY = GivingWay(LAYOUT, RULES, CONFIG, RobotTasker(LAYOUT, RULES), Rollout(LAYOUT, RULES, CONFIG))
WORLD = replace(initial_state(LAYOUT, RULES), tick=20)


def moment(human_still: int = 0) -> Moment:
    return Moment(WORLD, initial_kb(WORLD), ((Subtask.PICKUP_MEAT, 1.0),), 0, 42, human_still, False, True,
                  Subtask.PICKUP_ONION, FlickerWatch())


def test_in_a_joint_cycle_the_robot_steps_aside_drops_its_subtask_and_then_holds():
    cycling = Stance(Subtask.PICKUP_ONION, Standoff(), CycleWatch(returns=CONFIG.cycle_returns))
    action, stance = WAY.break_cycle(WORLD, cycling, Subtask.PICKUP_MEAT)
    assert action in (Action.NORTH, Action.SOUTH, Action.EAST, Action.WEST)
    assert stance.current is None and stance.cycle.broken == 1 and stance.cycle.hold_until > WORLD.tick
    held, same = WAY.break_cycle(replace(WORLD, tick=WORLD.tick + 1), stance, Subtask.PICKUP_MEAT)
    assert held is Action.STAY and same == stance
    assert WAY.break_cycle(WORLD, Stance(), Subtask.PICKUP_MEAT) == (None, Stance())


def test_without_a_standoff_the_options_pass_and_while_holding_aside_the_robot_stays():
    options = (Subtask.PICKUP_ONION, Subtask.PICKUP_MEAT)
    stance = Stance(Subtask.PICKUP_ONION)
    assert WAY.around_standoff(moment(), stance, Subtask.PICKUP_MEAT, options) == (options, stance)
    holding = replace(stance, standoff=Standoff(hold_until=WORLD.tick + 3))
    assert WAY.around_standoff(moment(), holding, Subtask.PICKUP_MEAT, options) == (Action.STAY, holding)


def test_after_the_standoff_the_given_up_subtask_is_avoided_and_a_still_persons_errand_taken_over():
    stuck = Stance(Subtask.PICKUP_ONION, Standoff(stuck=CONFIG.standoff_ticks))
    options = (Subtask.PICKUP_ONION, Subtask.PICKUP_MEAT)
    answer, stance = WAY.around_standoff(moment(), stuck, Subtask.PICKUP_MEAT, options)
    assert stance.standoff.avoid is Subtask.PICKUP_ONION and stance.standoff.stuck == 0
    assert answer == (Subtask.PICKUP_MEAT,), "the reachable other options"
    taken, stance = WAY.around_standoff(moment(CONFIG.standoff_ticks), stuck, Subtask.PICKUP_MEAT, options)
    assert isinstance(taken, Action) and stance.current is Subtask.PICKUP_MEAT


def test_waiting_at_a_station_beside_a_parked_person_the_robot_steps_aside():
    world = replace(WORLD, robot=AgentState((7, 2), Direction.NORTH), human=AgentState((8, 2), Direction.WEST))
    m = replace(moment(human_still=2), world=world)
    assert WAY.yield_if_blocking(m, Subtask.PICKUP_STEAK, Action.INTERACT) is not Action.INTERACT
    assert WAY.yield_if_blocking(replace(m, human_still=1), Subtask.PICKUP_STEAK, Action.INTERACT) is Action.INTERACT
    assert WAY.yield_if_blocking(m, Subtask.PICKUP_MEAT, Action.INTERACT) is Action.INTERACT
