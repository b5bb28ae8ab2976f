"""The kitchen as a standard environment (``planner/env``): PettingZoo's and Gymnasium's own conformance checks
pass, it is seeded, the person's observation is masked and the robot's full, and the robot's environment plays
the very trial ``steakhouse simulate`` plays for the same seed."""

from __future__ import annotations

import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env
from pettingzoo.test import parallel_api_test, parallel_seed_test

from planner.env.kitchen import KitchenEnv
from planner.env.observation import CHANNELS
from planner.env.single import RobotEnv
from planner.geometry import ACTIONS
from planner.partner import SimulatedPartner
from planner.play import TrialSettings, run_trial
from planner.rules import Rules
from study_config import load_layout

IN_VIEW = CHANNELS.index("in_view")


@pytest.mark.parametrize("kitchen", ["none_3", "practice"])
def test_pettingzoo_s_own_api_test_passes(kitchen):
    parallel_api_test(KitchenEnv(load_layout(kitchen)), num_cycles=1000)


def test_pettingzoo_s_seed_test_passes():
    parallel_seed_test(lambda: KitchenEnv(load_layout("practice")), num_cycles=50)


def test_gymnasium_s_env_checker_passes():
    check_env(RobotEnv(load_layout("none_3")), skip_render_check=True)


def test_the_person_sees_part_of_the_kitchen_and_the_robot_all_of_it():
    layout = load_layout("none_3")
    env = KitchenEnv(layout, fov_angle=120.0)
    observations, _ = env.reset(seed=3)
    rng = np.random.default_rng(3)
    for _ in range(40):
        person, robot = observations["human"]["grid"], observations["robot"]["grid"]
        assert robot[IN_VIEW].all(), "the robot sees every cell"
        assert 0 < person[IN_VIEW].sum() < layout.width * layout.height, "the person sees part of the kitchen"
        assert not person[:, person[IN_VIEW] == 0].any(), "nothing at all where the person does not look"
        observations, *_ = env.step({agent: int(rng.integers(len(ACTIONS))) for agent in env.agents})


def test_the_robot_s_environment_plays_the_trial_simulate_plays_for_the_same_seed():
    layout, rules = load_layout("practice"), Rules(orders=1)
    expected = run_trial(layout, 5, TrialSettings(rules=rules), robot=SimulatedPartner(layout, rules), record=True)
    env = RobotEnv(layout, rules)
    env.reset(seed=5)
    robot = SimulatedPartner(layout, rules)
    robot.reset(env.world)
    done = cut = False
    played = []
    total = 0.0
    while not (done or cut):
        action = robot.decide(env.world, env.events, env.robot_rng).action
        _, reward, done, cut, _ = env.step(ACTIONS.index(action))
        total += reward
        played.append(action)
    assert env.world.tick == expected.ticks and env.world == expected.final
    assert played == [r for _, r in expected.actions]
    assert total == expected.score and done == expected.finished


def test_the_same_seed_gives_the_same_episode():
    layout = load_layout("none_3")

    def episode(seed: int) -> list[bytes]:
        env = RobotEnv(layout)
        observation, _ = env.reset(seed=seed)
        frames = [observation["grid"].tobytes()]
        for action in np.random.default_rng(0).integers(len(ACTIONS), size=60):
            observation, *_ = env.step(int(action))
            frames.append(observation["grid"].tobytes() + env.world.human.facing.value.encode())
        return frames

    assert episode(11) == episode(11)
    assert episode(11) != episode(12), "the simulated person's choices come from the seed"
