"""How the participant's avatar walks their chosen subtask (``planner.avatar``): the first move of a shortest path to
the nearest target, an interaction once it faces it; the robot is avoided only where the participant can know it
is, and walked around once it has stood still for ``STUCK_TICKS``."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from planner.avatar import RobotWatch, avatar_move
from planner.fov import view
from planner.geometry import Action, Direction
from planner.human import STUCK_TICKS, HumanModel
from planner.kb import initial_kb
from planner.rules import Rules
from planner.state import AgentState, WorldState, initial_state
from planner.subtasks import Subtask
from study_config import load_layout

KITCHEN = load_layout("practice")  # onion crate (6,1), used from (6,2) facing north
RULES = Rules()
ANGLE = 120.0
MODEL = HumanModel(KITCHEN, RULES)


def world_at(human: tuple[int, int], facing: Direction, robot: tuple[int, int] = (2, 2)) -> WorldState:
    world = initial_state(KITCHEN, RULES)
    return replace(world, human=AgentState(human, facing, None), robot=AgentState(robot, Direction.SOUTH, None))


def move(world: WorldState, robot_known_at: tuple[int, int] | None = None,
         watch: RobotWatch = RobotWatch(), seed: int = 0) -> tuple[Action, bool]:
    kb = initial_kb(world)
    if robot_known_at is not None:
        kb = replace(kb, robot=AgentState(robot_known_at, Direction.SOUTH, None))
    return avatar_move(MODEL, ANGLE, world, kb, Subtask.PICKUP_ONION, watch, np.random.default_rng(seed))


def test_the_avatar_walks_toward_its_target_and_interacts_when_it_faces_it() -> None:
    assert move(world_at((4, 2), Direction.SOUTH)) == (Action.EAST, True)
    assert move(world_at((6, 2), Direction.NORTH)) == (Action.INTERACT, False)


def test_a_robot_the_participant_cannot_know_about_is_not_avoided() -> None:
    world = world_at((4, 2), Direction.WEST, robot=(5, 2))  # the robot is right behind them
    assert (5, 2) not in view(KITCHEN, (4, 2), Direction.WEST, ANGLE).cells
    assert move(world, robot_known_at=(2, 2))[0] is Action.EAST, "they walk into it, then face it"
    for seed in range(10):
        assert move(world, robot_known_at=(5, 2), seed=seed)[0] in (Action.SOUTH, Action.STAY), \
            "where they last saw it, it is avoided: a detour or a wait"


def test_a_robot_parked_for_long_enough_is_walked_around() -> None:
    world = world_at((4, 2), Direction.WEST, robot=(5, 2))
    watch = RobotWatch()
    for _ in range(STUCK_TICKS + 1):
        watch = watch.seen(world)
    assert watch.parked and watch.still == STUCK_TICKS
    for seed in range(10):
        assert move(world, robot_known_at=(5, 2), watch=watch, seed=seed) == (Action.SOUTH, True)


def test_the_watch_restarts_when_the_robot_moves() -> None:
    watch = RobotWatch().seen(world_at((4, 2), Direction.WEST, robot=(5, 2)))
    watch = watch.seen(world_at((4, 2), Direction.WEST, robot=(5, 2)))
    assert watch.still == 1 and not watch.parked
    moved = watch.seen(world_at((4, 2), Direction.WEST, robot=(5, 3)))
    assert (moved.last, moved.still) == ((5, 3), 0)
