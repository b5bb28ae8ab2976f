"""Joint cycles (planner.cycle): a robot and a person who step back and forth in step for
ever are seen to cycle, and the robot yields so both get through. The cycling pair is also played with the
rule switched off (``cycle_returns`` out of reach), to show it would otherwise cycle to the horizon."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from planner.cycle import CycleWatch, joint_key, watch
from planner.geometry import Action, Direction
from planner.human import HumanMemory, HumanModel
from planner.kb import KnowledgeBase
from planner.layout import Layout, parse_layout
from planner.planner_config import PlannerConfig
from planner.play import run_trial
from planner.robots import make_robot
from planner.rules import Rules
from planner.state import AgentState, WorldState, initial_state
from planner.step import step

RULES = Rules()
# A T-shaped kitchen: a top bar and a two-cell-wide stem down to the board and the serving counter.
T_KITCHEN = parse_layout("""XXXXXXXXXXX
XO  2   MPX
XD        X
XXXX  XXXXX
XXXB  SXXXX
XXXW 1XXXXX
XXXXXXXXXXX
""", name="t_kitchen")


class Decided:
    """The random choices of :class:`planner.human.HumanModel` made one way for good: it never waits when
    the robot is in its way and always takes the first detour (a person who always dodges the same way)."""

    def random(self) -> float:
        return 0.99

    def integers(self, n: int) -> int:
        return 0


class DodgingPerson:
    """The simulated person (docs/domain.md §4) with :class:`Decided` choices."""

    def __init__(self, layout: Layout) -> None:
        self.model = HumanModel(layout, RULES)

    def act(self, world: WorldState, kb: KnowledgeBase, memory: HumanMemory,
            rng: np.random.Generator) -> tuple[Action, HumanMemory]:
        return self.model.act(world, kb, memory, Decided())  # type: ignore[arg-type]


def test_the_cycling_pair_cycles_to_the_horizon_without_the_rule_and_finishes_with_it():
    # The baseline robot carries a clean plate up the stem, the person an onion down to the board; side by
    # side in the stem they step east and west together, tick after tick.
    off = run_trial(T_KITCHEN, 0, robot=make_robot("baseline", T_KITCHEN, RULES, PlannerConfig(cycle_returns=10**6)),
                    human=DodgingPerson(T_KITCHEN), record=True)
    assert not off.finished and off.cycles_broken == 0
    world, keys = initial_state(T_KITCHEN, RULES), []
    for human, robot in off.actions:
        world, _ = step(T_KITCHEN, world, {"human": human, "robot": robot}, RULES)
        keys.append(joint_key(world))
    assert len(set(keys[-100:])) <= 4, "the pair should have been going round the same few joint situations"
    assert keys[-1] == keys[-3] != keys[-2]
    on = run_trial(T_KITCHEN, 0, robot=make_robot("baseline", T_KITCHEN, RULES, PlannerConfig()),
                   human=DodgingPerson(T_KITCHEN))
    assert on.finished, f"the pair should have finished, not stopped at tick {on.ticks}"
    assert on.cycles_broken >= 1


def test_returns_count_a_cycle_but_not_waiting():
    world = initial_state(T_KITCHEN, RULES)
    east = replace(world, robot=AgentState((5, 2), Direction.EAST), human=AgentState((6, 2), Direction.EAST))
    west = replace(world, robot=AgentState((4, 2), Direction.WEST), human=AgentState((5, 2), Direction.WEST))
    state = CycleWatch()
    for w in [east, west] * 5:
        state = watch(state, w, 0.0, 16, robot_moved=True)
    assert state.returns == 8 and state.cycling(8)
    waiting = CycleWatch()
    for _ in range(10):
        waiting = watch(waiting, east, 0.0, 16, robot_moved=False)
    assert waiting.returns == 0, "standing still is no cycle"
    shuttling = CycleWatch()
    for held in ["dirty_plate", None] * 5:
        shuttling = watch(shuttling, replace(east, human=replace(east.human, held=held)), 0.0, 16, robot_moved=False)
    assert shuttling.returns == 0, "the person going round alone while the robot waits is no joint cycle"
    pushing = CycleWatch()
    for _ in range(10):
        pushing = watch(pushing, east, 0.0, 16, robot_moved=True)
    assert pushing.returns == 9, "bumping into each other tick after tick is a cycle of one tick"
    progress = CycleWatch()
    for phi, w in enumerate([east, west] * 5):
        progress = watch(progress, w, float(phi), 16, robot_moved=True)
    assert progress.returns == 0, "the team's potential moved every tick"
