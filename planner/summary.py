"""The compact status summary of a world or a KB, and the KB gap (docs/domain.md §6, paper §VII).

Components: grill status (empty / cooking / ready), board status (empty / chopping / ready), sink status
(empty / washing / clean; the states are ``planner.vocabulary``'s) and the robot's held object. The KB gap at a
tick is the number of components where the human's KB differs from the world (a kind with several stations differs
if any of them does).
"""

from __future__ import annotations

from dataclasses import dataclass

from planner.kb import KnowledgeBase
from planner.rules import Rules
from planner.state import WorldState
from planner.vocabulary import StationState, Terrain, station_state

GAP_COMPONENTS: tuple[str, ...] = ("grill", "board", "sink", "robot_held")


@dataclass(frozen=True, slots=True)
class Summary:
    grills: tuple[StationState, ...]
    boards: tuple[StationState, ...]
    sinks: tuple[StationState, ...]
    robot_held: str | None

    def to_dict(self) -> dict[str, object]:
        return {"grill": list(self.grills), "board": list(self.boards), "sink": list(self.sinks),
                "robot_held": self.robot_held}


def summarize(statuses: WorldState | KnowledgeBase, rules: Rules) -> Summary:
    """The summary of a world state or of a KB (the same fields in both)."""
    robot = statuses.robot
    return Summary(
        grills=tuple(station_state(Terrain.GRILL, g, rules.cook_time) for g in statuses.grills),
        boards=tuple(station_state(Terrain.BOARD, b, rules.chop_time) for b in statuses.boards),
        sinks=tuple(station_state(Terrain.SINK, s, rules.wash_time) for s in statuses.sinks),
        robot_held=None if robot is None else robot.held,
    )


def gap_components(kb: Summary, world: Summary) -> dict[str, int]:
    """1 for each component where the KB differs from the world, else 0 (from two summaries)."""
    return {
        "grill": int(kb.grills != world.grills),
        "board": int(kb.boards != world.boards),
        "sink": int(kb.sinks != world.sinks),
        "robot_held": int(kb.robot_held != world.robot_held),
    }


def kb_gap_components(kb: KnowledgeBase, world: WorldState, rules: Rules) -> dict[str, int]:
    """The same as ``gap_components(summarize(kb), summarize(world))``, without building summaries."""
    robot_held = None if kb.robot is None else kb.robot.held
    return {
        "grill": int(not _same(kb.grills, world.grills, rules.cook_time)),
        "board": int(not _same(kb.boards, world.boards, rules.chop_time)),
        "sink": int(not _same(kb.sinks, world.sinks, rules.wash_time)),
        "robot_held": int(robot_held != world.robot.held),
    }


def _same(believed: tuple[int | None, ...], actual: tuple[int | None, ...], done_at: int) -> bool:
    if believed == actual:
        return True
    for a, b in zip(believed, actual, strict=False):
        if (a is None) != (b is None) or (a is not None and b is not None and (a >= done_at) != (b >= done_at)):
            return False
    return True


def kb_gap(kb: KnowledgeBase, world: WorldState, rules: Rules) -> int:
    """The KB gap at one tick: the number of differing components."""
    return sum(kb_gap_components(kb, world, rules).values())
