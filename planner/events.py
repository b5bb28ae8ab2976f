"""What happened in one step, for logs, the knowledge base ("own actions enter at once") and metrics."""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

from planner.geometry import Pos


class EventKind(str, Enum):
    PICK_UP = "pick_up"            # from a counter
    PUT_DOWN = "put_down"          # onto an empty counter
    SWAP = "swap"                  # held object swapped with a counter's
    DISPENSE = "dispense"          # took an onion / meat / dirty plate from a dispenser
    START_COOKING = "start_cooking"
    PLATE_STEAK = "plate_steak"    # clean plate took the ready steak
    LOAD_SINK = "load_sink"
    WASH = "wash"
    TAKE_CLEAN_PLATE = "take_clean_plate"
    LOAD_BOARD = "load_board"
    CHOP = "chop"
    GARNISH = "garnish"            # plated steak took the chopped garnish
    DELIVER = "deliver"
    BLOCKED = "blocked"            # a move cancelled by a collision (same cell or swap)


@dataclass(frozen=True, slots=True)
class Event:
    """One agent's effect on one cell: ``agent`` is ``"human"`` or ``"robot"``; ``obj`` the object involved."""

    agent: str
    kind: EventKind
    pos: Pos
    obj: str | None = None

    def to_dict(self) -> dict[str, object]:
        return {"agent": self.agent, "kind": self.kind.value, "pos": list(self.pos), "obj": self.obj}
