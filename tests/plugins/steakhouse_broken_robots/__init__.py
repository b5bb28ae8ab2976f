"""Robot plug-ins that fail in each way the platform must survive (docs/robots.md, "When a robot fails"), registered
by ``../steakhouse_broken_robots-0.1.dist-info/entry_points.txt``: found by ``importlib.metadata`` when this folder is
on ``sys.path`` (the ``broken_robots`` fixture of ``tests/conftest.py``), never installed.

Each decides well for its first ``GOOD_TICKS`` decisions (so a trial gets going), then fails: ``broken_raises``
raises, ``broken_hangs`` never returns, ``broken_illegal`` answers an action that is not one of the six.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from planner.robot_api import Action, Decision, Event, KnowledgeBase, Layout, Person, RobotPlugin, Rules, WorldState

GOOD_TICKS = 2


@dataclass(frozen=True)
class Settings:
    good_ticks: int = GOOD_TICKS


class Failing:
    def __init__(self, how: str, good_ticks: int) -> None:
        self.how, self.good_ticks, self.calls = how, good_ticks, 0

    def reset(self, world: WorldState, kb: KnowledgeBase | None = None) -> None:
        self.calls = 0

    def decide(self, world: WorldState, events: Sequence[Event], rng: np.random.Generator,
               deadline: float | None = None) -> Decision:
        self.calls += 1
        if self.calls <= self.good_ticks:
            return Decision(Action.STAY)
        if self.how == "raises":
            raise RuntimeError("the lab's planner has a bug")
        if self.how == "hangs":
            while True:
                time.sleep(0.01)
        return Decision("fly")  # type: ignore[arg-type]  # the illegal answer under test


def _plugin(how: str) -> RobotPlugin[Settings]:
    def make(kitchen: Layout, rules: Rules, person: Person, settings: Settings) -> Failing:
        return Failing(how, settings.good_ticks)

    return RobotPlugin(make=make, settings=Settings, summary=f"tests: {how}")


RAISES = _plugin("raises")
HANGS = _plugin("hangs")
ILLEGAL = _plugin("illegal")
