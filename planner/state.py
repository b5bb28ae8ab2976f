"""The moving part of the world: immutable, hashable, JSON round-trip (STYLE 1).

Station statuses are kept per station in the layout's reading order:
``grills[i]`` is ``None`` (empty) or the cook count of the meat on grill ``i`` (ready at ``cook_time``);
``boards[i]`` ``None`` or the chop count of the onion (chopped garnish at ``chop_time``);
``sinks[i]`` ``None`` or the wash count of the plate (clean at ``wash_time``).
Objects on counters are ``(pos, object)`` pairs sorted by position, at most one per counter.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

from planner.geometry import Direction, Pos
from planner.layout import Layout
from planner.objects import OBJECTS
from planner.rules import Rules

AGENTS: tuple[str, str] = ("robot", "human")


@dataclass(frozen=True, slots=True)
class AgentState:
    pos: Pos
    facing: Direction
    held: str | None = None

    def to_dict(self) -> dict[str, Any]:
        return {"pos": list(self.pos), "facing": self.facing.value, "held": self.held}

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> AgentState:
        held = data.get("held")
        if held is not None and held not in OBJECTS:
            raise ValueError(f"unknown held object {held!r}")
        return cls(pos=_pos(data["pos"]), facing=Direction(data["facing"]), held=held)


@dataclass(frozen=True, slots=True)
class WorldState:
    human: AgentState
    robot: AgentState
    objects: tuple[tuple[Pos, str], ...]
    grills: tuple[int | None, ...]
    boards: tuple[int | None, ...]
    sinks: tuple[int | None, ...]
    orders_left: int
    tick: int = 0
    score: int = 0

    def agent(self, name: str) -> AgentState:
        return self.human if name == "human" else self.robot

    def with_agent(self, name: str, agent: AgentState) -> WorldState:
        return replace(self, human=agent) if name == "human" else replace(self, robot=agent)

    def object_at(self, pos: Pos) -> str | None:
        for where, obj in self.objects:
            if where == pos:
                return obj
        return None

    def to_dict(self) -> dict[str, Any]:
        return {
            "human": self.human.to_dict(),
            "robot": self.robot.to_dict(),
            "objects": [{"pos": list(p), "obj": o} for p, o in self.objects],
            "grills": list(self.grills),
            "boards": list(self.boards),
            "sinks": list(self.sinks),
            "orders_left": self.orders_left,
            "tick": self.tick,
            "score": self.score,
        }

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> WorldState:
        objects = []
        for item in data["objects"]:
            if item["obj"] not in OBJECTS:
                raise ValueError(f"unknown object {item['obj']!r}")
            objects.append((_pos(item["pos"]), item["obj"]))
        return cls(
            human=AgentState.from_dict(data["human"]),
            robot=AgentState.from_dict(data["robot"]),
            objects=tuple(sorted(objects)),
            grills=tuple(_count(v) for v in data["grills"]),
            boards=tuple(_count(v) for v in data["boards"]),
            sinks=tuple(_count(v) for v in data["sinks"]),
            orders_left=int(data["orders_left"]),
            tick=int(data["tick"]),
            score=int(data["score"]),
        )


def initial_state(layout: Layout, rules: Rules) -> WorldState:
    """Both agents on their start cells facing south, holding nothing; no objects; all orders open."""
    return WorldState(
        human=AgentState(layout.start("human"), Direction.SOUTH),
        robot=AgentState(layout.start("robot"), Direction.SOUTH),
        objects=(),
        grills=(None,) * len(layout.grills),
        boards=(None,) * len(layout.boards),
        sinks=(None,) * len(layout.sinks),
        orders_left=rules.orders,
    )


def is_done(state: WorldState, rules: Rules) -> bool:
    """A trial ends when every order is delivered or the horizon is reached."""
    return state.orders_left <= 0 or state.tick >= rules.horizon


def _pos(value: Any) -> Pos:
    x, y = value
    return (int(x), int(y))


def _count(value: Any) -> int | None:
    return None if value is None else int(value)
