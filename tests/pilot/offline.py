"""An offline trial for the pilot tests: the server's own engine and masking (``server.game``), the simulated
participant answering each masked frame, the robot played by the simulated human model."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from pilot.client import respond
from pilot.config import ParticipantConfig
from pilot.mind import Mind
from pilot.perception import Perception
from planner.human import HumanMemory, HumanModel
from planner.kb import omniscient_kb
from planner.subtasks import Subtask
from server.game import snapshot
from server.game.engine import TrialEngine
from server.game.needs import NEEDS
from server.protocol.interrupts import Interrupt
from study_config.catalog import LoadedStudy


@dataclass
class OfflineTrial:
    engine: TrialEngine
    frames: list[dict[str, Any]] = field(default_factory=list)
    sent: list[dict[str, Any]] = field(default_factory=list)
    perceptions: list[Perception] = field(default_factory=list)
    server_kbs: list[Any] = field(default_factory=list)


def play_offline(loaded: LoadedStudy, kitchen: str, config: ParticipantConfig, seed: int,
                 max_ticks: int = 400) -> OfflineTrial:
    layout, rules, world = loaded.layout(kitchen), loaded.rules, loaded.study.world
    engine = TrialEngine(layout, rules, angle=world.fov_angle, kb_delay=world.kb_delay, seed=seed)
    trial = OfflineTrial(engine)
    robot = HumanModel(layout, rules, me="robot")
    memory = HumanMemory()
    robot_rng = np.random.default_rng([seed, 99])
    rng = np.random.default_rng([seed, 0])
    needs = {s.value: need for s, need in NEEDS.items()}
    seen = Perception(layout.width, layout.height, tuple(loaded.layouts.values()))
    mind = Mind()
    while not engine.done and engine.tick < max_ticks:
        frame = snapshot.state(engine, mode="fixed_rate", rate=5.0, ack=0).model_dump(mode="json")
        seen, mind, body = respond(mind, seen, frame, needs, loaded, config, rng)
        trial.frames.append(frame)
        trial.sent.append(body)
        trial.perceptions.append(seen)
        trial.server_kbs.append(engine.kb)
        if body["type"] == "select_subtask":
            engine.controller.select(Subtask(body["subtask"]), engine.world.human.held)
        elif body["type"] == "interrupt":
            engine.controller.interrupt(Interrupt(body["action"]))
        action, memory = robot.act(engine.world, omniscient_kb(engine.world), memory, robot_rng)
        engine.advance(action)
    return trial
