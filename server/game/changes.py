"""Who last changed each cell, so that a task refused because the world changed under the participant is told
what changed — "The robot took the steak from the grill" — from the world's events, never from a guess about what
the cook holds (docs/protocol.md, "Blocked subtasks").

Every counter, grill, board and sink remembers the last event that changed what it holds (a take, a put, a
chop or wash). What a station or counter holds changes only by such events (a steak cooking changes its state, not
what the grill holds), so the last one is why it holds what it holds now. A refusal at a cell — the one the cook
faces, or the one its task was heading for — is explained by that event when the robot made it and its kind
answers the refusal: something missing (the robot took it), a station busy (the robot put something there), or
work already done (the robot chopped or washed). The participant is looking at the cell or has just learnt what it
holds, and the robot is the only other cook, so the message reveals nothing hidden beyond who did it.

Immutable: :meth:`Changes.after` returns the next value, once per world step.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Literal

from planner.events import Event, EventKind
from planner.geometry import Pos
from planner.layout import Layout, Terrain

Category = Literal["taken", "used", "done"]

TAKEN: dict[EventKind, str] = {EventKind.PLATE_STEAK: "steak", EventKind.TAKE_CLEAN_PLATE: "clean_plate",
                               EventKind.GARNISH: "garnish"}
"""Events that take what a station held, and the thing taken (on a counter: ``pick_up`` and ``swap``, the object)."""
USED: frozenset[EventKind] = frozenset({EventKind.START_COOKING, EventKind.LOAD_BOARD, EventKind.LOAD_SINK,
                                       EventKind.PUT_DOWN})
"""Events that fill a station or a counter."""
DONE: dict[EventKind, str] = {EventKind.CHOP: "onion", EventKind.WASH: "dirty_plate"}
"""Work on a station, and what was worked on."""
PLACES: dict[Terrain, str] = {Terrain.GRILL: "grill", Terrain.BOARD: "board", Terrain.SINK: "sink",
                              Terrain.COUNTER: "counter"}


@dataclass(frozen=True, slots=True)
class Change:
    """One event at a cell: who, its category, the thing it names and the place (``grill``, ``board``, ``sink``,
    ``counter``)."""

    agent: str
    category: Category
    item: str | None
    place: str


def change_of(layout: Layout, event: Event) -> Change | None:
    """The change an event made to what its cell holds, or ``None`` (a move, a dispenser, a delivery)."""
    entry = layout.stations.get(event.pos)
    place = PLACES.get(entry[0]) if entry is not None else None
    if place is None:
        return None
    kind = event.kind
    if kind in TAKEN:
        return Change(event.agent, "taken", TAKEN[kind], place)
    if kind in (EventKind.PICK_UP, EventKind.SWAP):
        return Change(event.agent, "taken", event.obj, place)
    if kind in USED:
        return Change(event.agent, "used", event.obj, place)
    if kind in DONE:
        return Change(event.agent, "done", DONE[kind], place)
    return None


@dataclass(frozen=True, slots=True)
class Changes:
    """The last change of each cell that has had one."""

    last: Mapping[Pos, Change] = field(default_factory=lambda: MappingProxyType({}))

    def after(self, layout: Layout, events: Iterable[Event]) -> Changes:
        """The changes after one step's ``events``."""
        found = {e.pos: c for e in events if (c := change_of(layout, e)) is not None}
        return Changes(MappingProxyType({**self.last, **found})) if found else self

    def by_robot(self, cells: Iterable[Pos], category: Category) -> Change | None:
        """The robot's change of ``category`` that is the last change of one of ``cells`` (the first such cell in
        that order), or ``None``."""
        for cell in cells:
            change = self.last.get(cell)
            if change is not None and change.agent == "robot" and change.category == category:
                return change
        return None
