"""The compact status summary of a world or a KB, and the two KB gaps (docs/domain.md §6, paper §VII).

**The reference's gap** (``kb_diff``, the paper's measure as its code computes it): the KB and the world each
reduce to four values, the reference's *state info*: the grill (1 if a steak is on it, else 0), the board (the
onion's chop count, −1 when empty), the sink (the plate's wash count, −1 when empty) and what the robot holds.
Per component the gap is ``|KB − world|``, except that a KB exactly 3 above the world counts 1 (believing the
garnish ready or the plate clean where there is none), and 1 when the robot's held object differs. A kitchen with
several grills, boards or sinks reduces each kind as the reference reduces the world: a steak on any grill, the
largest count. Per trial (``kb_diff_trial``): the share of ticks with any gap (``kb_diff_freq``, %), the mean gap
over those ticks (``kb_diff_avg``) and over all ticks (``kb_diff_mean``).

**Our older status gap** (``gap_components``): grill status (empty / cooking / ready), board status (empty /
chopping / ready), sink status (empty / washing / clean; the states are ``planner.vocabulary``'s) and the robot's
held object, 0 or 1 each (a kind with several stations differs if any of them does).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from planner.kb import KnowledgeBase
from planner.objects import CLEAN_PLATE, DIRTY_PLATE, DISH, MEAT, ONION, STEAK_PLATE
from planner.rules import Rules
from planner.state import WorldState
from planner.vocabulary import StationState, Terrain, station_state

GAP_COMPONENTS: tuple[str, ...] = ("grill", "board", "sink", "robot_held")
REFERENCE_NAMES: dict[str, str] = {MEAT: "meat", ONION: "onion", DIRTY_PLATE: "plate", CLEAN_PLATE: "hot_plate",
                                   STEAK_PLATE: "steak", DISH: "dish"}
"""What the robot holds, by the reference's names (its keys spell them so)."""
_OUR_NAMES = {ref: ours for ours, ref in REFERENCE_NAMES.items()}
KB_DIFF_MAX = 8.0
"""The largest reference gap of one tick: grill 1, board 3, sink 3 (chop and wash counts 0-2, −1 empty), robot 1."""


@dataclass(frozen=True, slots=True)
class StateInfo:
    """The reference's state info of a KB or a world (module docstring)."""

    grill: int
    board: int
    sink: int
    robot_held: str | None

    def key(self) -> str:
        """The reference's key, ``grill.board.sink.robot_held`` (e.g. ``1.2.-1.hot_plate``)."""
        held = "None" if self.robot_held is None else REFERENCE_NAMES[self.robot_held]
        return f"{self.grill}.{self.board}.{self.sink}.{held}"

    def to_dict(self) -> dict[str, object]:
        return {"grill": self.grill, "board": self.board, "sink": self.sink, "robot_held": self.robot_held}

    @classmethod
    def from_key(cls, key: str) -> StateInfo:
        grill, board, sink, held = key.split(".")
        return cls(int(grill), int(board), int(sink), None if held == "None" else _OUR_NAMES[held])


def state_info(statuses: WorldState | KnowledgeBase) -> StateInfo:
    """The reference's state info of a world (a steak counts on the grill once it has cooked a tick) or of a KB
    (a steak believed on a grill counts)."""
    if isinstance(statuses, WorldState):
        grill = int(any(g is not None and g > 0 for g in statuses.grills))
    else:
        grill = int(any(g is not None for g in statuses.grills))
    robot = statuses.robot
    return StateInfo(grill, max((b for b in statuses.boards if b is not None), default=-1),
                     max((s for s in statuses.sinks if s is not None), default=-1),
                     None if robot is None else robot.held)


def reference_key(statuses: WorldState | KnowledgeBase) -> str:
    return state_info(statuses).key()


def info_diff(kb: StateInfo, world: StateInfo) -> dict[str, int]:
    """The reference's gap per component (module docstring)."""
    out: dict[str, int] = {}
    for name, believed, actual in (("grill", kb.grill, world.grill), ("board", kb.board, world.board),
                                   ("sink", kb.sink, world.sink)):
        diff = believed - actual
        out[name] = 1 if diff == 3 else abs(diff)
    out["robot_held"] = int(kb.robot_held != world.robot_held)
    return out


def kb_diff(kb: str | StateInfo, world: str | StateInfo) -> dict[str, int]:
    """:func:`info_diff` of two state infos or of their keys."""
    return info_diff(kb if isinstance(kb, StateInfo) else StateInfo.from_key(kb),
                     world if isinstance(world, StateInfo) else StateInfo.from_key(world))


def kb_diff_trial(diffs: Sequence[dict[str, int]]) -> tuple[float, float | None, float]:
    """``kb_diff_freq`` (% of ticks with a gap), ``kb_diff_avg`` (mean gap over those ticks; ``None`` when no tick
    has one) and ``kb_diff_mean`` (mean gap over all ticks) of one trial's per-tick gaps."""
    totals = [sum(d.values()) for d in diffs]
    with_gap = [t for t in totals if t > 0]
    if not totals:
        return 0.0, None, 0.0
    return (100.0 * len(with_gap) / len(totals), sum(with_gap) / len(with_gap) if with_gap else None,
            sum(totals) / len(totals))


@dataclass(frozen=True, slots=True)
class Summary:
    """The statuses of a world or a KB, and the reference's state info of it (``reference``)."""

    grills: tuple[StationState, ...]
    boards: tuple[StationState, ...]
    sinks: tuple[StationState, ...]
    robot_held: str | None
    reference: StateInfo | None = None

    def to_dict(self) -> dict[str, object]:
        out: dict[str, object] = {"grill": list(self.grills), "board": list(self.boards), "sink": list(self.sinks),
                                  "robot_held": self.robot_held}
        if self.reference is not None:
            out["reference"] = self.reference.to_dict()
        return out


def summarize(statuses: WorldState | KnowledgeBase, rules: Rules) -> Summary:
    """The summary of a world state or of a KB (the same fields in both)."""
    robot = statuses.robot
    return Summary(
        grills=tuple(station_state(Terrain.GRILL, g, rules.cook_time) for g in statuses.grills),
        boards=tuple(station_state(Terrain.BOARD, b, rules.chop_time) for b in statuses.boards),
        sinks=tuple(station_state(Terrain.SINK, s, rules.wash_time) for s in statuses.sinks),
        robot_held=None if robot is None else robot.held, reference=state_info(statuses),
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


def kb_diff_of_summaries(kb_summary: Mapping[str, Any], world_summary: Mapping[str, Any]) -> dict[str, int] | None:
    """The reference's gap of one tick from its stored KB and world summaries (``None`` when they were stored
    without the reference's state info)."""
    kb, world = kb_summary.get("reference"), world_summary.get("reference")
    if not isinstance(kb, Mapping) or not isinstance(world, Mapping):
        return None
    return info_diff(_info(kb), _info(world))


def _info(data: Mapping[str, Any]) -> StateInfo:
    held = data.get("robot_held")
    return StateInfo(int(data["grill"]), int(data["board"]), int(data["sink"]), None if held is None else str(held))
