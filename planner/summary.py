"""The compact status summary of a world or a KB, and the KB gap (docs/domain.md §6, paper §VII).

Components: grill status (empty / cooking / ready), board status (empty / chopping / ready), sink status
(empty / washing / clean) and the robot's held object. The KB gap at a tick is the number of components
where the human's KB differs from the world (a kind with several stations differs if any of them does).
"""

from __future__ import annotations

from dataclasses import dataclass

from planner.kb import KnowledgeBase
from planner.rules import Rules
from planner.state import WorldState

GAP_COMPONENTS: tuple[str, ...] = ("grill", "board", "sink", "robot_held")


@dataclass(frozen=True, slots=True)
class Summary:
    grills: tuple[str, ...]
    boards: tuple[str, ...]
    sinks: tuple[str, ...]
    robot_held: str | None

    def to_dict(self) -> dict[str, object]:
        return {"grill": list(self.grills), "board": list(self.boards), "sink": list(self.sinks),
                "robot_held": self.robot_held}


def _status(value: int | None, done_at: int, working: str, done: str) -> str:
    if value is None:
        return "empty"
    return done if value >= done_at else working


def summarize(statuses: WorldState | KnowledgeBase, rules: Rules) -> Summary:
    """The summary of a world state or of a KB (the same fields in both)."""
    robot = statuses.robot
    return Summary(
        grills=tuple(_status(g, rules.cook_time, "cooking", "ready") for g in statuses.grills),
        boards=tuple(_status(b, rules.chop_time, "chopping", "ready") for b in statuses.boards),
        sinks=tuple(_status(s, rules.wash_time, "washing", "clean") for s in statuses.sinks),
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
    for a, b in zip(believed, actual, strict=True):
        if (a is None) != (b is None) or (a is not None and b is not None and (a >= done_at) != (b >= done_at)):
            return False
    return True


def kb_gap(kb: KnowledgeBase, world: WorldState, rules: Rules) -> int:
    """The KB gap at one tick: the number of differing components."""
    return sum(kb_gap_components(kb, world, rules).values())
