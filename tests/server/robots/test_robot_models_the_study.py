"""The robot models the person the study shows: the study's FOV angle and KB delay reach the
planner, in-process and in worker processes, and its model of the participant's KB is the one the server
logs for the participant, tick by tick, also after the trial resumes from the store."""

from __future__ import annotations

import asyncio
import time
from collections.abc import Sequence
from dataclasses import replace

import numpy as np
from steakhouse_testing import Player, play_to_end, play_until, until_unloaded

from planner import robot_catalog
from planner.decision import Decision, Robot
from planner.events import Event
from planner.kb import KnowledgeBase, initial_kb
from planner.layout import Layout
from planner.planner_config import PlannerConfig
from planner.qmdp import QmdpRobot
from planner.robot_api import Person
from planner.robot_catalog import RobotFactory, RobotSetup
from planner.robots import make_robot
from planner.rules import Rules
from planner.state import WorldState, initial_state
from server.robots import ProcessRobots
from store import trials
from study_config import load_layout


class Recording:
    """The real planner, keeping its modelled KB after each decision (by the tick it decided on)."""

    def __init__(self, robot: QmdpRobot) -> None:
        self.robot = robot
        self.kbs: dict[int, dict[str, object]] = {}

    def reset(self, world: WorldState, kb: KnowledgeBase | None = None) -> None:
        self.robot.reset(world, kb)

    def decide(self, world: WorldState, events: Sequence[Event], rng: np.random.Generator,
               deadline: float | None = None) -> Decision:
        decision = self.robot.decide(world, events, rng, None)
        assert self.robot.kb is not None
        self.kbs[world.tick] = self.robot.kb.to_dict()
        return decision


def recording_factory(built: list[Recording]) -> RobotFactory:
    """The catalogue's robot, each robot built appended to ``built`` as a :class:`Recording`."""

    def factory(name: str, layout: Layout, rules: Rules, setup: RobotSetup) -> Robot:
        # A short lookahead keeps every decision inside its tick on a busy machine (a late one is dropped
        # and the requests queued behind it are cancelled at the trial's end); the model of the person
        # does not depend on it.
        robot = robot_catalog.build(name, layout, rules,
                                    replace(setup, settings=(*setup.settings, ("search_depth", 1))))
        assert isinstance(robot, QmdpRobot)
        built.append(Recording(robot))
        return built[-1]

    return factory


STUDY = {"kitchens": ["none_3"], "robots": ["fov_aware"],
         "timing": {"mode": "wait_for_participant", "tick_rate_hz": 10},
         "world": {"orders": 1, "horizon": 60, "fov_angle": 90, "kb_delay": 5}}


def logged_kbs(server, trial_id: int) -> dict[int, dict[str, object]]:
    with server.services.store.transaction() as session:
        return {t.tick: t.kb_state for t in trials.ticks(session, trial_id)}


def test_a_90_degree_5_tick_study_gets_a_robot_that_models_exactly_that_person(live_server, study_file):
    built: list[Recording] = []
    server = live_server([study_file(**STUDY)], robot_factory=recording_factory(built))

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
    logged = logged_kbs(server, hello["trial"]["id"])
    assert len(logged) == end["ticks"] >= 20
    decided = sorted(set(logged) & set(robot.kbs))
    assert decided == sorted(logged)[:-1] or decided == sorted(logged), "the robot saw every tick but the last"
    mismatched = [t for t in decided if robot.kbs[t] != logged[t]]
    assert not mismatched, f"the robot's model of the person's KB differs from the logged one at ticks {mismatched}"


def test_a_resumed_trials_robot_goes_on_from_the_logged_model_of_the_person(live_server, study_file):
    """The trial is unloaded (grace window over, ``after_grace: resume``) and rebuilt from the store, as after a
    server restart or failover: the new robot's model of the person's KB is the restored one, not the whole
    kitchen as the person would know it at a trial's start."""
    built: list[Recording] = []
    server = live_server([study_file(**STUDY, reconnect={"grace_seconds": 0.3, "after_grace": "resume"})],
                         robot_factory=recording_factory(built))

    async def scenario():
        player = Player(server.url)
        await player.ready()
        first = await player.socket()
        hello = await first.recv()
        await play_until(first, 15)
        await first.close()
        await until_unloaded(server.services)
        second = await player.socket()
        resumed = await second.recv()
        end = await play_to_end(second)
        await second.close()
        await player.close()
        return hello, resumed, end

    hello, resumed, end = asyncio.run(scenario())
    assert resumed["trial"]["id"] == hello["trial"]["id"] and resumed["resumed"] is True
    start = resumed["tick"]
    assert start >= 15 and end["ticks"] > start + 1
    _, robot = built
    logged = logged_kbs(server, hello["trial"]["id"])
    decided = sorted(robot.kbs)
    assert decided[0] == start and start + 1 in decided
    assert robot.kbs[start + 1] == logged[start + 1], "the tick after the resume"
    mismatched = [t for t in decided if robot.kbs[t] != logged[t]]
    assert not mismatched, f"the robot's model of the person's KB differs from the logged one at ticks {mismatched}"


def test_the_baseline_keeps_its_omniscient_model_of_the_person_when_reset_with_a_restored_kb():
    layout = load_layout("practice")
    rules = Rules()
    world = initial_state(layout, rules)
    restored = replace(initial_kb(world), robot=None)
    for name, expected in (("fov_aware", restored), ("no_rollout", restored), ("baseline", initial_kb(world))):
        robot = make_robot(name, layout, rules, PlannerConfig(human_angle=90.0, human_delay=5))
        assert isinstance(robot, QmdpRobot)
        robot.reset(world, restored)
        assert robot.kb == expected, name


def test_the_study_config_and_the_restored_kb_reach_a_worker_process():
    layout = load_layout("practice")
    rules = Rules(cook_time=4)
    world = initial_state(layout, rules)

    async def run():
        pool = ProcessRobots(1, "steakhouse_test_robots:config_echo")
        await pool.start()
        try:
            await pool.open(1, "fov_aware", layout, rules, RobotSetup(Person(fov_angle=90.0, kb_delay=5)), world,
                            replace(initial_kb(world), robot=None))
            return await pool.decide(1, world, (), 1, 0, time.monotonic() + 5.0)
        finally:
            await pool.shutdown()

    choice = asyncio.run(run())
    assert choice.error is None and choice.info is not None
    assert choice.info["q_values"] == {"angle": 90.0, "delay": 5.0, "kb_robot": 0.0}, "the config and the KB"
