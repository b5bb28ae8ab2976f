"""The kitchen as a PettingZoo ``ParallelEnv`` (docs/robots.md, "The environment"): two agents, ``human`` and
``robot``, each taking one of the six actions per step; the world steps by :func:`planner.step.step`, the game's
own rules.

Observations (:mod:`planner.env.observation`): the person's masked with the trial's field of view by the same
function as the participant's frames (:func:`planner.masking.masked`), the robot's full (360°). Actions:
``Discrete(6)``, the index in :data:`planner.geometry.ACTIONS` (north, south, east, west, stay, interact).
Rewards: both agents get the points delivered this step (the team's score, ``Rules.delivery_reward`` per dish).
An episode terminates when every order is delivered and is truncated at the horizon. The robot's info carries the
step's events (what a robot may read besides the world); the person's is empty. The world itself is
:attr:`KitchenEnv.world` (a robot plug-in reads it, not the arrays). Nothing here is random: ``reset(seed=…)``
seeds the action spaces' sampling only.
"""

from __future__ import annotations

from typing import Any, ClassVar

import numpy as np
from gymnasium import spaces
from pettingzoo import ParallelEnv

from planner.env.observation import CHANNELS, HUD, observe
from planner.events import Event
from planner.geometry import ACTIONS, Action
from planner.layout import Layout
from planner.perception import FOV_ANGLE
from planner.rules import Rules
from planner.state import AGENTS, WorldState, initial_state
from planner.step import step

Observation = dict[str, np.ndarray]
_STAY = ACTIONS.index(Action.STAY)
"""The action of an agent left out of a step's actions (one whose episode is over)."""


def observation_space(layout: Layout, rules: Rules) -> spaces.Dict:
    """The space of one cook's observation in ``layout`` (:mod:`planner.env.observation`)."""
    most = max(rules.horizon, rules.orders, rules.orders * rules.delivery_reward)
    return spaces.Dict({
        "grid": spaces.Box(0, 255, (len(CHANNELS), layout.height, layout.width), np.uint8),
        "hud": spaces.Box(0, most, (len(HUD),), np.int32),
    })


class KitchenEnv(ParallelEnv[str, Observation, int]):  # type: ignore[misc]  # pettingzoo ships no types
    """One kitchen (``layout`` with its numbers ``rules``), the person seeing ``fov_angle`` degrees."""

    metadata: ClassVar[dict[str, Any]] = {"name": "steakhouse_kitchen_v0", "render_modes": ["ansi"],
                                          "is_parallelizable": True}

    def __init__(self, layout: Layout, rules: Rules | None = None, fov_angle: float = FOV_ANGLE,
                 render_mode: str | None = None) -> None:
        self.layout, self.rules, self.fov_angle = layout, rules or Rules(), float(fov_angle)
        self.render_mode = render_mode
        self.possible_agents = ["human", "robot"]
        self.agents: list[str] = []
        self._observation_space = observation_space(layout, self.rules)
        self._action_space = {agent: spaces.Discrete(len(ACTIONS)) for agent in self.possible_agents}
        self.world: WorldState = initial_state(layout, self.rules)
        self.events: tuple[Event, ...] = ()

    def observation_space(self, agent: str) -> spaces.Dict:
        return self._observation_space

    def action_space(self, agent: str) -> spaces.Discrete:
        return self._action_space[agent]

    def _observations(self) -> dict[str, Observation]:
        return {agent: observe(self.layout, self.world, self.rules, self.angle(agent), agent) for agent in self.agents}

    def angle(self, agent: str) -> float:
        """The field of view an agent observes with: the person's, or 360° for the robot."""
        return self.fov_angle if agent == "human" else 360.0

    def _infos(self) -> dict[str, dict[str, Any]]:
        return {agent: ({"events": self.events} if agent == "robot" else {}) for agent in self.agents}

    def reset(self, seed: int | None = None,
              options: dict[str, Any] | None = None) -> tuple[dict[str, Observation], dict[str, dict[str, Any]]]:
        if seed is not None:
            for i, agent in enumerate(self.possible_agents):
                self._action_space[agent].seed(seed + i)
        self.agents = list(self.possible_agents)
        self.world, self.events = initial_state(self.layout, self.rules), ()
        return self._observations(), self._infos()

    def step(self, actions: dict[str, int]) -> tuple[dict[str, Observation], dict[str, float], dict[str, bool],
                                                      dict[str, bool], dict[str, dict[str, Any]]]:
        if not self.agents:
            raise RuntimeError("the episode is over: call reset()")
        joint = {agent: ACTIONS[int(actions.get(agent, _STAY))] for agent in AGENTS}
        before = self.world.score
        self.world, self.events = step(self.layout, self.world, joint, self.rules)
        reward = float(self.world.score - before)
        done = self.world.orders_left <= 0
        cut = not done and self.world.tick >= self.rules.horizon
        observations, infos = self._observations(), self._infos()
        rewards = dict.fromkeys(self.agents, reward)
        terminations = dict.fromkeys(self.agents, done)
        truncations = dict.fromkeys(self.agents, cut)
        if done or cut:
            self.agents = []
        return observations, rewards, terminations, truncations, infos

    def render(self) -> str | None:
        if self.render_mode != "ansi":
            return None
        rows = [list(row) for row in self.layout.rows]
        for name, mark in (("robot", "R"), ("human", "H")):
            x, y = self.world.agent(name).pos
            rows[y][x] = mark
        return "\n".join("".join(row) for row in rows)

    def close(self) -> None:
        return None
