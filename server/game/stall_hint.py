"""The participant is told when the team is stuck (docs/client.md, "Stall hints"; docs/protocol.md ``stall_hint``).

When the team's potential has not moved for the study's ``timing.stall_hint_seconds`` (default 8 s) — the
shaping potential of :func:`planner.rollout.potential`: orders left, steaks on grills, boards and sinks in use,
clean plates, plated steaks and dishes — the participant gets one hint, and another only after the team has
moved on and stalled again. The hint is phrased only from what the participant knows — where they stand, what
they hold, and their own knowledge of the kitchen (the modelled KB, docs/domain.md §3) — and never names the
robot's planner or the condition. In order, the first that applies:

1. ``standing_at_station``: they stand on the only cell from which a station is used ("You are standing where
   the board is used");
2. ``onion_needs_chopping`` / ``plate_needs_washing``: their KB has an onion on a board not yet chopped, or a
   plate in a sink not yet washed ("The onion you put on the board still needs chopping" when they put it
   there);
3. ``holding``: they hold something ("You are still holding the onion");
4. ``look_around``: nothing else they know of ("Nothing has moved on for a while: look around for what is
   needed next").

State is an immutable :class:`StallWatch`, advanced once per tick by :func:`advance` (a live trial keeps it in a
:class:`StallHints`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

from planner.events import Event, EventKind
from planner.geometry import DIRECTIONS, Pos
from planner.kb import KnowledgeBase
from planner.layout import Layout, Terrain, access_cells
from planner.planner_config import PlannerConfig
from planner.rollout import potential
from planner.rules import Rules
from planner.state import WorldState
from planner.vocabulary import CLEAN_PLATE, DIRTY_PLATE, DISH, MEAT, ONION, STEAK_PLATE
from server.protocol.server import StallHintCode

STATION_NAMES: dict[Terrain, str] = {
    Terrain.BOARD: "board", Terrain.GRILL: "grill", Terrain.SINK: "sink", Terrain.SERVE: "serving counter",
    Terrain.ONION: "onion crate", Terrain.MEAT: "meat crate", Terrain.PLATE: "plate rack"}
"""The stations in the order a hint names them, with the words the participant's screen uses."""
OBJECT_NAMES: dict[str, str] = {ONION: "onion", MEAT: "meat", DIRTY_PLATE: "dirty plate", CLEAN_PLATE: "clean plate",
                                STEAK_PLATE: "plated steak", DISH: "dish"}
_SCORE = PlannerConfig()


@dataclass(frozen=True, slots=True)
class Hint:
    code: StallHintCode
    text: str


@dataclass(frozen=True, slots=True)
class StallWatch:
    phi: float | None = None
    """The team's potential at the last tick."""
    quiet: int = 0
    """Ticks without a change of the potential."""
    hinted: bool = False
    """A hint was given in this quiet stretch."""
    loaded_by_you: frozenset[Pos] = frozenset()
    """Boards and sinks the participant loaded last."""


class StallHints:
    """One live trial's watch (advanced once per tick), the ticks a stall must last, and how many hints it gave."""

    def __init__(self, ticks: int) -> None:
        self.ticks = ticks
        self.watch = StallWatch()
        self.given = 0

    def step(self, layout: Layout, rules: Rules, world: WorldState, kb: KnowledgeBase,
             events: Sequence[Event]) -> Hint | None:
        """Advance the watch by one step (see :func:`advance`); the hint to give now, counted, if any."""
        self.watch, hint = advance(self.watch, layout, rules, world, kb, events, self.ticks)
        if hint is not None:
            self.given += 1
        return hint


def advance(state: StallWatch, layout: Layout, rules: Rules, world: WorldState, kb: KnowledgeBase,
            events: Sequence[Event], ticks: int) -> tuple[StallWatch, Hint | None]:
    """The watch after one step to ``world`` (``kb``: the participant's KB after it; ``events``: the step's), and
    the hint to give now, if any (``ticks``: the study's ``stall_hint_seconds`` in ticks)."""
    loaded = set(state.loaded_by_you)
    for e in events:
        if e.kind in (EventKind.LOAD_BOARD, EventKind.LOAD_SINK):
            (loaded.add if e.agent == "human" else loaded.discard)(e.pos)
    phi = potential(world, _SCORE)
    moved_on = state.phi is None or phi != state.phi
    state = replace(state, phi=phi, quiet=0 if moved_on else state.quiet + 1,
                    hinted=state.hinted and not moved_on, loaded_by_you=frozenset(loaded))
    if state.hinted or state.quiet < ticks:
        return state, None
    return replace(state, hinted=True), hint_for(layout, rules, world, kb, state.loaded_by_you)


def hint_for(layout: Layout, rules: Rules, world: WorldState, kb: KnowledgeBase,
             loaded_by_you: frozenset[Pos] = frozenset()) -> Hint:
    """The hint for the participant now (the module's list, first that applies)."""
    you = world.human
    beside = [d.ahead(you.pos) for d in DIRECTIONS]
    for kind, name in STATION_NAMES.items():
        if any(layout.terrain(cell) is kind and access_cells(layout, cell) == (you.pos,) for cell in beside):
            return Hint("standing_at_station", f"You are standing where the {name} is used.")
    for cell, count in zip(layout.boards, kb.boards, strict=False):
        if count is not None and count < rules.chop_time:
            whose = "you put " if cell in loaded_by_you else ""
            return Hint("onion_needs_chopping", f"The onion {whose}on the board still needs chopping.")
    for cell, count in zip(layout.sinks, kb.sinks, strict=False):
        if count is not None and count < rules.wash_time:
            whose = "you put " if cell in loaded_by_you else ""
            return Hint("plate_needs_washing", f"The plate {whose}in the sink still needs washing.")
    if you.held is not None:
        return Hint("holding", f"You are still holding the {OBJECT_NAMES.get(you.held, you.held)}.")
    return Hint("look_around", "Nothing has moved on for a while: look around for what is needed next.")

