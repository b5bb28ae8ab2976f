"""``mylab_scripted``: a robot that follows a fixed recipe (the example of docs/robots.md, step 1: write it).

Each tick it looks at the true world (what a robot may read) and does the first thing of its recipe it can: carry
what it holds on (meat to an empty grill, an onion to an empty board, a dirty plate to an empty sink, a clean plate
to a ready steak, a plated steak to a chopped garnish, the dish to the serving counter); with empty hands, chop or
wash what is under way, take a clean plate for a steak, or fetch what the orders still need, in the order of its
``first`` setting. It puts down what it cannot use and, blocked, steps aside at random (from the trial's stream).
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np

from mylab_robots.skills import cells_of, free_counters, walk
from planner.robot_api import (
    Action,
    Decision,
    Event,
    KnowledgeBase,
    Layout,
    NoSettings,
    Person,
    RobotPlugin,
    Rules,
    Terrain,
    WorldState,
)

__all__ = ["PLUGIN", "NoSettings", "Scripted", "ScriptedSettings"]

Need = Literal["meat", "onion", "plate"]


@dataclass(frozen=True)
class ScriptedSettings:
    """``first``: what it fetches first when the orders need everything; ``patience``: ticks it waits for a
    station to free up before putting its load down."""

    first: Need = "meat"
    patience: int = 6


class Scripted:
    def __init__(self, layout: Layout, rules: Rules, settings: ScriptedSettings) -> None:
        self.layout, self.rules, self.settings = layout, rules, settings
        self.waited = 0

    def reset(self, world: WorldState, kb: KnowledgeBase | None = None) -> None:
        self.waited = 0

    def decide(self, world: WorldState, events: Sequence[Event], rng: np.random.Generator,
               deadline: float | None = None) -> Decision:
        start = time.perf_counter()
        targets = self.targets(world)
        action = walk(self.layout, world, targets) if targets else None
        if action is None or action is Action.STAY:
            self.waited += 1
            if world.robot.held is not None and self.waited > self.settings.patience:
                action = walk(self.layout, world, free_counters(self.layout, world))
            if action is None or action is Action.STAY:
                moves = (Action.NORTH, Action.SOUTH, Action.EAST, Action.WEST, Action.STAY)
                action = moves[int(rng.integers(len(moves)))] if self.waited > 2 else Action.STAY
        else:
            self.waited = 0
        return Decision(action, elapsed_ms=(time.perf_counter() - start) * 1000)

    def at(self, kind: Terrain, status: tuple[int | None, ...], ok: object) -> tuple[tuple[int, int], ...]:
        cells = cells_of(self.layout, kind)
        return tuple(cell for cell, value in zip(cells, status, strict=True) if _test(ok, value, self.rules, kind))

    def targets(self, world: WorldState) -> tuple[tuple[int, int], ...]:
        held, lay = world.robot.held, self.layout
        if held == "meat":
            return self.at(Terrain.GRILL, world.grills, "empty")
        if held == "onion":
            return self.at(Terrain.BOARD, world.boards, "empty")
        if held == "dirty_plate":
            return self.at(Terrain.SINK, world.sinks, "empty")
        if held == "clean_plate":
            return self.at(Terrain.GRILL, world.grills, "done")
        if held == "steak_plate":
            return self.at(Terrain.BOARD, world.boards, "done")
        if held == "dish":
            return cells_of(lay, Terrain.SERVE)
        working = self.at(Terrain.BOARD, world.boards, "working") + self.at(Terrain.SINK, world.sinks, "working")
        if working:
            return working
        cooking = any(g is not None for g in world.grills)
        if cooking and self.at(Terrain.SINK, world.sinks, "done"):
            return self.at(Terrain.SINK, world.sinks, "done")
        needs = {"meat": not cooking and world.human.held != "meat",
                 "onion": all(b is None for b in world.boards) and world.human.held != "onion",
                 "plate": all(s is None for s in world.sinks) and world.human.held not in ("dirty_plate",
                                                                                           "clean_plate")}
        order = [self.settings.first, *(n for n in ("meat", "onion", "plate") if n != self.settings.first)]
        kinds = {"meat": Terrain.MEAT, "onion": Terrain.ONION, "plate": Terrain.PLATE}
        for need in order:
            if needs[need]:
                return cells_of(lay, kinds[need])
        return ()


def _test(ok: object, value: int | None, rules: Rules, kind: Terrain) -> bool:
    total = rules.cook_time if kind is Terrain.GRILL else rules.chop_time if kind is Terrain.BOARD else rules.wash_time
    if ok == "empty":
        return value is None
    if ok == "done":
        return value is not None and value >= total
    return value is not None and value < total


def make(kitchen: Layout, rules: Rules, person: Person, settings: ScriptedSettings) -> Scripted:
    return Scripted(kitchen, rules, settings)


PLUGIN = RobotPlugin(make=make, settings=ScriptedSettings, summary="example: a fixed recipe (mylab-robots)")
"""What the entry point ``mylab_scripted`` names (step 2 of docs/robots.md: register it)."""
