"""The kitchen environment's person sees exactly what a participant's browser receives: for the same states, the
person's observation (``planner/env``) holds the cells, objects, station states and robot of the server's masked
frame (``server/game/view.py``, ``server/game/snapshot.py``), nothing more, nothing less."""

from __future__ import annotations

import numpy as np
import pytest

from planner.env.kitchen import KitchenEnv
from planner.env.observation import CHANNELS
from planner.geometry import ACTIONS, DIRECTIONS
from planner.vocabulary import OBJECTS
from server.game.view import agent_view, visible_world
from study_config import load_layout

AT = {name: i for i, name in enumerate(CHANNELS)}
STATE = {"empty": 0, "cooking": 1, "chopping": 1, "washing": 1, "ready": 2, "clean": 2}
FACING = {d.value: i + 1 for i, d in enumerate(DIRECTIONS)}


def frame_grid(cells, you, robot, shape) -> np.ndarray:
    """The server's frame (its cell views, the participant's own agent view, the robot's if in view) written into
    the observation's planes, from the message parts alone."""
    grid = np.zeros(shape, dtype=np.uint8)
    for cell in cells:
        x, y = cell.x, cell.y
        grid[AT["in_view"], y, x] = 1
        grid[AT[f"terrain_{cell.terrain}"], y, x] = 1
        if cell.object is not None:
            grid[AT[f"object_{cell.object}"], y, x] = 1
        if cell.station is not None:
            grid[AT["station_progress"], y, x] = cell.station.progress
            grid[AT["station_state"], y, x] = STATE[cell.station.state]
    for who, agent in (("me", you), ("other", robot)):
        if agent is not None:
            grid[AT[who], agent.y, agent.x] = 1
            grid[AT[f"{who}_facing"], agent.y, agent.x] = FACING[agent.facing]
            grid[AT[f"{who}_held"], agent.y, agent.x] = OBJECTS.index(agent.held) + 1 if agent.held else 0
    return grid


@pytest.mark.parametrize("kitchen,angle", [("none_3", 120.0), ("mid_2", 90.0), ("practice", 200.0)])
def test_the_person_s_observation_is_the_participant_s_frame(kitchen, angle):
    layout = load_layout(kitchen)
    env = KitchenEnv(layout, fov_angle=angle)
    observations, _ = env.reset(seed=1)
    rng = np.random.default_rng(1)
    compared = with_robot = with_things = 0
    # Biased to interact, so objects and busy stations come into view.
    weights = np.array([0.15, 0.15, 0.15, 0.15, 0.05, 0.35])
    while env.agents and compared < 400:
        world = env.world
        cells, robot = visible_world(layout, world, env.rules, angle)
        expected = frame_grid(cells, agent_view(world.human), robot, observations["human"]["grid"].shape)
        assert np.array_equal(observations["human"]["grid"], expected), f"tick {world.tick}"
        assert tuple(observations["human"]["hud"]) == (world.tick, world.orders_left, world.score)
        compared += 1
        with_robot += robot is not None
        with_things += any(c.object is not None or (c.station is not None and c.station.state != "empty")
                           for c in cells)
        actions = {agent: int(rng.choice(len(ACTIONS), p=weights)) for agent in env.agents}
        observations, *_ = env.step(actions)
    assert compared >= 100 and with_robot > 0 and with_things > 0, (compared, with_robot, with_things)
