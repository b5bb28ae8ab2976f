"""The robot's side of the kitchen as a Gymnasium ``Env`` (docs/robots.md, "The environment"): the person is the
simulated human (:mod:`planner.human`, docs/domain.md §4), FOV-limited, with its KB and its delay, as in
``steakhouse simulate``.

Observation: the robot's (:mod:`planner.env.observation`, full view); action: ``Discrete(6)``
(:data:`planner.geometry.ACTIONS`); reward: the points delivered this step; terminated when every order is
delivered, truncated at the horizon. ``reset(seed=s)`` gives the person the random stream
:func:`planner.play.run_trial` gives it for seed ``s`` (and :attr:`RobotEnv.robot_rng` the robot's), so a policy
played here plays the same trial as in ``simulate``. The world, the last step's events and the person's KB are
:attr:`RobotEnv.world`, :attr:`RobotEnv.events` and :attr:`RobotEnv.kb`.
"""

from __future__ import annotations

from typing import Any

import gymnasium
import numpy as np
from gymnasium import spaces

from planner.env.kitchen import Observation, observation_space
from planner.env.observation import observe
from planner.events import Event
from planner.geometry import ACTIONS
from planner.human import HumanMemory, HumanModel
from planner.kb import KnowledgeBase, initial_kb, update_kb
from planner.layout import Layout
from planner.partner import HumanPolicy
from planner.perception import FOV_ANGLE, KB_DELAY
from planner.rules import Rules
from planner.state import WorldState, initial_state
from planner.step import step


class RobotEnv(gymnasium.Env[dict[str, Any], np.int64]):
    """One kitchen, the robot the learner, the person the simulated human seeing ``fov_angle`` degrees and
    acknowledging what stayed ``kb_delay`` ticks in view (or ``human``, another partner model)."""

    metadata = {"render_modes": ["ansi"]}  # noqa: RUF012  # gymnasium declares it an instance variable

    def __init__(self, layout: Layout, rules: Rules | None = None, fov_angle: float = FOV_ANGLE,
                 kb_delay: int = KB_DELAY, human: HumanPolicy | None = None, render_mode: str | None = None) -> None:
        self.layout, self.rules = layout, rules or Rules()
        self.fov_angle, self.kb_delay = float(fov_angle), kb_delay
        self.human: HumanPolicy = human if human is not None else HumanModel(layout, self.rules)
        self.render_mode = render_mode
        self.observation_space = observation_space(layout, self.rules)
        self.action_space = spaces.Discrete(len(ACTIONS))
        self.world: WorldState = initial_state(layout, self.rules)
        self.kb: KnowledgeBase = initial_kb(self.world)
        self.events: tuple[Event, ...] = ()
        self.memory = HumanMemory()
        self.human_rng, self.robot_rng = np.random.default_rng(0).spawn(2)

    def _observation(self) -> Observation:
        return observe(self.layout, self.world, self.rules, 360.0, "robot")

    def reset(self, *, seed: int | None = None,
              options: dict[str, Any] | None = None) -> tuple[Observation, dict[str, Any]]:
        super().reset(seed=seed)
        source = np.random.default_rng(seed) if seed is not None else self.np_random
        self.human_rng, self.robot_rng = source.spawn(2)
        self.world = initial_state(self.layout, self.rules)
        self.kb, self.memory, self.events = initial_kb(self.world), HumanMemory(), ()
        return self._observation(), {"events": self.events}

    def step(self, action: np.int64 | int) -> tuple[Observation, float, bool, bool, dict[str, Any]]:
        h_action, self.memory = self.human.act(self.world, self.kb, self.memory, self.human_rng)
        before = self.world.score
        self.world, self.events = step(self.layout, self.world, {"human": h_action, "robot": ACTIONS[int(action)]},
                                       self.rules)
        self.kb = update_kb(self.kb, self.layout, self.world, angle=self.fov_angle, kb_delay=self.kb_delay,
                            own_events=[e for e in self.events if e.agent == "human"])
        done = self.world.orders_left <= 0
        cut = not done and self.world.tick >= self.rules.horizon
        return self._observation(), float(self.world.score - before), done, cut, {"events": self.events}

    def render(self) -> str | None:
        if self.render_mode != "ansi":
            return None
        rows = [list(row) for row in self.layout.rows]
        for name, mark in (("robot", "R"), ("human", "H")):
            x, y = self.world.agent(name).pos
            rows[y][x] = mark
        return "\n".join("".join(row) for row in rows)
