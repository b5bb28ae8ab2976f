"""``mylab_learned``: a policy learned in the kitchen environment (``train.py``; docs/robots.md, "The environment").

The policy chooses among skills (:data:`SKILLS`: walk to a kind of station and use it, put down or pick up at a
counter, wait a tick) by a table of values learned with Q-learning over the robot's observation in
``planner.env.single.RobotEnv`` (the simulated FOV-limited person as partner). Its state (:func:`features`) is read
from that observation, which the robot computes from the world it is given with the environment's own function
(``planner.env.observation.observe``), so it sees here exactly what it saw in training. A state the table has
never seen gets a skill drawn from the trial's random stream. The table (``q_table.json``) is made by
``train.py`` (its command is in the README and in the table's ``about``).
"""

from __future__ import annotations

import json
import time
from collections.abc import Sequence
from dataclasses import dataclass
from importlib import resources

import numpy as np

from mylab_robots.skills import cells_of, free_counters, walk
from planner.env.observation import CHANNELS, observe
from planner.robot_api import (
    Action,
    Decision,
    Event,
    KnowledgeBase,
    Layout,
    Person,
    Pos,
    RobotPlugin,
    Rules,
    Terrain,
    WorldState,
)

SKILLS: tuple[str, ...] = ("meat", "onion", "plate", "grill", "board", "sink", "serve", "counter", "wait")
MAX_SKILL_TICKS = 25
"""A skill that has not reached its station after this many ticks ends (the policy chooses again)."""
_AT = {name: i for i, name in enumerate(CHANNELS)}
_KINDS = {"meat": Terrain.MEAT, "onion": Terrain.ONION, "plate": Terrain.PLATE, "grill": Terrain.GRILL,
          "board": Terrain.BOARD, "sink": Terrain.SINK, "serve": Terrain.SERVE}
State = tuple[int, ...]


def features(observation: dict[str, np.ndarray]) -> State:
    """The policy's state, from the robot's observation: what the robot and the person hold, the most advanced
    grill, board and sink (0 empty, 1 working, 2 done) and the orders left (at most 2)."""
    grid, hud = observation["grid"], observation["hud"]
    me, other = grid[_AT["me"]] == 1, grid[_AT["other"]] == 1
    held = int(grid[_AT["me_held"]][me].max(initial=0))
    partner = int(grid[_AT["other_held"]][other].max(initial=0))
    state = grid[_AT["station_state"]]
    stations = tuple(int(state[grid[_AT[f"terrain_{kind}"]] == 1].max(initial=0))
                     for kind in ("grill", "board", "sink"))
    return (held, partner, *stations, min(int(hud[1]), 2))


def skill_targets(layout: Layout, world: WorldState, skill: str) -> tuple[Pos, ...]:
    """The cells skill ``skill`` walks to and uses."""
    if skill == "counter":
        if world.robot.held is not None:
            return free_counters(layout, world)
        return tuple(pos for pos, _ in world.objects)
    return cells_of(layout, _KINDS[skill]) if skill in _KINDS else ()


@dataclass
class SkillRun:
    """The skill under way and how long it has run."""

    skill: str
    ticks: int = 0


def skill_action(layout: Layout, world: WorldState, run: SkillRun) -> tuple[Action, bool]:
    """The action of the skill under way this tick, and whether the skill ends with it."""
    run.ticks += 1
    if run.skill == "wait":
        return Action.STAY, True
    action = walk(layout, world, skill_targets(layout, world, run.skill))
    if action is None:
        return Action.STAY, True
    return action, action is Action.INTERACT or run.ticks >= MAX_SKILL_TICKS


def load_table(text: str) -> dict[State, np.ndarray]:
    data = json.loads(text)
    if data.get("skills") != list(SKILLS):
        raise ValueError(f"the table was learned for skills {data.get('skills')}, not {list(SKILLS)}")
    return {tuple(int(v) for v in key.split(",")): np.array(values, dtype=float) for key, values in data["q"].items()}


def dump_table(table: dict[State, np.ndarray], about: dict[str, object]) -> str:
    rows = {",".join(str(v) for v in key): [round(float(q), 4) for q in values]
            for key, values in sorted(table.items())}
    return json.dumps({"skills": list(SKILLS), "about": about, "q": rows}, indent=0, sort_keys=True)


@dataclass(frozen=True)
class LearnedSettings:
    """``table``: the file of learned values (default: the one shipped in the package)."""

    table: str = ""


class Learned:
    def __init__(self, layout: Layout, rules: Rules, table: dict[State, np.ndarray]) -> None:
        self.layout, self.rules, self.table = layout, rules, table
        self.run: SkillRun | None = None

    def reset(self, world: WorldState, kb: KnowledgeBase | None = None) -> None:
        self.run = None

    def decide(self, world: WorldState, events: Sequence[Event], rng: np.random.Generator,
               deadline: float | None = None) -> Decision:
        start = time.perf_counter()
        values: dict[str, float] = {}
        if self.run is None:
            state = features(observe(self.layout, world, self.rules, 360.0, "robot"))
            known = self.table.get(state)
            if known is None:
                choice = int(rng.integers(len(SKILLS)))
            else:
                choice = int(np.argmax(known))
                values = {skill: float(q) for skill, q in zip(SKILLS, known, strict=True)}
            self.run = SkillRun(SKILLS[choice])
        action, ended = skill_action(self.layout, world, self.run)
        if ended:
            self.run = None
        return Decision(action, q_values=values, elapsed_ms=(time.perf_counter() - start) * 1000)


def make(kitchen: Layout, rules: Rules, person: Person, settings: LearnedSettings) -> Learned:
    if settings.table:
        with open(settings.table, encoding="utf-8") as handle:
            text = handle.read()
    else:
        text = resources.files("mylab_robots").joinpath("q_table.json").read_text(encoding="utf-8")
    return Learned(kitchen, rules, load_table(text))


PLUGIN = RobotPlugin(make=make, settings=LearnedSettings,
                     summary="example: skills chosen by a Q-table learned in the environment (mylab-robots)")
"""What the entry point ``mylab_learned`` names."""
