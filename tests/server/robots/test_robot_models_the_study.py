"""The robot models the person the study shows (issue 13): the study's FOV angle and KB delay reach the
planner, in-process and in worker processes, and its model of the participant's KB is the one the server
logs for the participant, tick by tick."""

from __future__ import annotations

import asyncio
import time
from collections.abc import Sequence
from dataclasses import replace

import numpy as np
from steakhouse_testing import Player, play_to_end

from planner.decision import Decision, Robot
from planner.events import Event
from planner.layout import Layout
from planner.planner_config import PlannerConfig
from planner.qmdp import QmdpRobot
from planner.robots import make_robot
from planner.rules import Rules
from planner.state import WorldState, initial_state
from server.robots import ProcessRobots
from server.store import trials
from study_config import load_layout


class Recording:
    """The real planner, keeping its modelled KB after each decision (by the tick it decided on)."""

    def __init__(self, robot: QmdpRobot) -> None:
        self.robot = robot
        self.kbs: dict[int, dict[str, object]] = {}

    def reset(self, world: WorldState) -> None:
        self.robot.reset(world)

    def decide(self, world: WorldState, events: Sequence[Event], rng: np.random.Generator,
               deadline: float | None = None) -> Decision:
        decision = self.robot.decide(world, events, rng, None)
        assert self.robot.kb is not None
        self.kbs[world.tick] = self.robot.kb.to_dict()
        return decision


def test_a_90_degree_5_tick_study_gets_a_robot_that_models_exactly_that_person(live_server, study_file):
    built: list[Recording] = []

    def factory(name: str, layout: Layout, rules: Rules, config: PlannerConfig) -> Robot:
        # A short lookahead keeps every decision inside its tick on a busy machine (a late one is dropped
        # and the requests queued behind it are cancelled at the trial's end); the model of the person
        # does not depend on it.
        robot = make_robot(name, layout, rules, replace(config, search_depth=1))
        assert isinstance(robot, QmdpRobot)
        built.append(Recording(robot))
        return built[-1]

    server = live_server([study_file(kitchens=["none_3"], robots=["fov_aware"],
                                     timing={"mode": "wait_for_participant", "tick_rate_hz": 10},
                                     world={"orders": 1, "horizon": 60, "fov_angle": 90, "kb_delay": 5})],
                         robot_factory=factory)

    async def scenario():
        player = Player(server.url)
        await player.ready()
        sock = await player.socket()
        hello = await sock.recv()
        end = await play_to_end(sock)
        await sock.close()
        await player.close()
        return hello, end

    hello, end = asyncio.run(scenario())
    (robot,) = built
    assert (robot.robot.cfg.human_angle, robot.robot.cfg.human_delay) == (90, 5)
    with server.services.store.transaction() as session:
        logged = {t.tick: t.kb_state for t in trials.ticks(session, hello["trial"]["id"])}
    assert len(logged) == end["ticks"] >= 20
    decided = sorted(set(logged) & set(robot.kbs))
    assert decided == sorted(logged)[:-1] or decided == sorted(logged), "the robot saw every tick but the last"
    mismatched = [t for t in decided if robot.kbs[t] != logged[t]]
    assert not mismatched, f"the robot's model of the person's KB differs from the logged one at ticks {mismatched}"


def test_the_study_config_reaches_a_worker_process():
    layout = load_layout("practice")
    rules = Rules(cook_time=4)
    world = initial_state(layout, rules)

    async def run():
        pool = ProcessRobots(1, "steakhouse_test_robots:config_echo")
        await pool.start()
        try:
            await pool.open(1, "fov_aware", layout, rules, PlannerConfig(human_angle=90.0, human_delay=5), world)
            return await pool.decide(1, world, (), 1, 0, time.monotonic() + 5.0)
        finally:
            await pool.shutdown()

    choice = asyncio.run(run())
    assert choice.error is None and choice.info is not None
    assert choice.info["q_values"] == {"angle": 90.0, "delay": 5.0}
