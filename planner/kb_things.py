"""Which object is which from one tick to the next: the identities the KB's acknowledgement rule counts by
(docs/domain.md §3).

The rule counts the ticks each *object* has been in view, wherever it is carried, so the KB needs to know, tick
after tick, that the onion now in the robot's hands is the one that lay on the counter. The world state has no
identities; this module gives every object one and carries it along. An object keeps its identity while it
lies, is carried, is put down or swapped, and while a station works on it; the plated steak is the steak that
cooked on the grill and the clean plate taken from the sink is the plate washed there. A new object appears
when something is taken from a crate and when a station takes in what it is given (meat on the grill becomes a
steak, an onion on the board a garnish, a dirty plate in the sink a plate being washed) or the garnish is added
(a dish); the held object is then gone, as is a delivered dish.

Each agent's interaction of the step is read from what its hands held before and hold now and from the cell it
faces (an agent that interacted did not move), the robot's first and then the person's, as the world steps. The
person's own step events name a swap of two equal objects, which the hands cannot show. Whatever the reading
cannot explain (a world that jumped, as in a test or a resumed trial) is taken as it is: objects that vanished
are gone, objects that appeared are new.

An object's *kind* is the reference's name for it (``KINDS``), since its rule guesses objects by these names.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

from planner.events import Event, EventKind
from planner.geometry import Pos
from planner.layout import Layout, Terrain
from planner.objects import CLEAN_PLATE, DIRTY_PLATE, DISH, MEAT, ONION, STEAK_PLATE
from planner.state import AgentState, WorldState

Place = Pos | str
"""A cell (a counter or a station) or an agent's hands (``"robot"``, ``"human"``)."""

KINDS: dict[str, str] = {MEAT: "meat", ONION: "onion", DIRTY_PLATE: "plate", CLEAN_PLATE: "hot_plate",
                         STEAK_PLATE: "steak", DISH: "dish"}
"""Our object names → the reference's names of the same objects (a clean plate is its ``hot_plate``, a plated
steak its ``steak``)."""
OBJECT_OF_KIND: dict[str, str] = {kind: obj for obj, kind in KINDS.items()}
STATION_KINDS: dict[Terrain, str] = {Terrain.GRILL: "steak", Terrain.BOARD: "garnish", Terrain.SINK: "hot_plate"}
"""What a grill, board or sink holds, by the reference's names."""
_CRATES = (Terrain.ONION, Terrain.MEAT, Terrain.PLATE)


@dataclass(frozen=True, slots=True)
class Thing:
    """One object of the world: its identity, where it is, its kind and its count (cook, chop or wash count of
    what a station holds; ``None`` otherwise)."""

    id: int
    place: Place
    kind: str
    state: int | None = None

    def at(self, place: Place) -> Thing:
        return Thing(self.id, place, self.kind, self.state)


@dataclass(frozen=True, slots=True)
class Things:
    """Every object of the world with its identity: those lying on counters and in stations in the order they
    arrived where they are (the reference's order of objects, whose last one its rule picks), then the robot's,
    then the person's held object; ``next_id`` is the identity the next new object gets."""

    lying: tuple[Thing, ...]
    robot: Thing | None
    human: Thing | None
    next_id: int

    def ordered(self) -> tuple[Thing, ...]:
        held = tuple(t for t in (self.robot, self.human) if t is not None)
        return self.lying + held

    def to_list(self) -> list[object]:
        return [[t.id, list(t.place) if isinstance(t.place, tuple) else t.place, t.kind, t.state]
                for t in self.ordered()] + [self.next_id]

    @classmethod
    def from_list(cls, data: list[Any]) -> Things:
        """The inverse of :meth:`to_list`."""
        *items, next_id = data
        lying: list[Thing] = []
        hands: dict[str, Thing] = {}
        for ident, place, kind, state in items:
            where: Place = str(place) if isinstance(place, str) else (int(place[0]), int(place[1]))
            thing = Thing(int(ident), where, str(kind), None if state is None else int(state))
            if isinstance(where, str):
                hands[where] = thing
            else:
                lying.append(thing)
        return cls(tuple(lying), hands.get("robot"), hands.get("human"), int(next_id))


def kind_at(layout: Layout, cell: Pos, obj: str | None) -> str | None:
    """The kind of what lies at ``cell``: ``obj`` on a counter, the station's own kind in a grill, board or sink."""
    entry = layout.stations.get(cell)
    if entry is not None and entry[0] in STATION_KINDS:
        return STATION_KINDS[entry[0]]
    return None if obj is None else KINDS[obj]


def first_things(layout: Layout, world: WorldState) -> Things:
    """Identities for a world seen for the first time: every object new, in reading order."""
    return reconcile(Things((), None, None, 0), layout, world)


def advance(things: Things, layout: Layout, world: WorldState, human_events: Iterable[Event] = ()) -> Things:
    """The identities after one step that led to ``world`` (module docstring)."""
    swapped = any(e.kind is EventKind.SWAP for e in human_events)
    if not swapped and _same_hands(things.robot, world.robot) and _same_hands(things.human, world.human):
        return reconcile(things, layout, world)  # nobody interacted: most ticks
    w = _Working(things)
    for agent, state in (("robot", world.robot), ("human", world.human)):
        w.interact(layout, agent, state, same_swap=agent == "human" and swapped)
    return reconcile(Things(tuple(w.lying.values()), w.hands["robot"], w.hands["human"], w.next_id), layout, world)


def _same_hands(thing: Thing | None, agent: AgentState) -> bool:
    """Whether the agent holds what it held (by kind), so that its step moved no object (:meth:`_Working.interact`
    reads no interaction then, a swap of equal objects aside)."""
    return (None if thing is None else OBJECT_OF_KIND.get(thing.kind)) == agent.held


class _Working:
    __slots__ = ("hands", "lying", "next_id")

    def __init__(self, things: Things) -> None:
        self.lying: dict[Pos, Thing] = {t.place: t for t in things.lying if isinstance(t.place, tuple)}
        self.hands: dict[str, Thing | None] = {"robot": things.robot, "human": things.human}
        self.next_id = things.next_id

    def new(self, place: Place, kind: str) -> Thing:
        self.next_id += 1
        return Thing(self.next_id - 1, place, kind)

    def lay(self, cell: Pos, thing: Thing) -> None:
        self.lying.pop(cell, None)
        self.lying[cell] = thing.at(cell)

    def interact(self, layout: Layout, agent: str, state: AgentState, *, same_swap: bool) -> None:
        before = self.hands[agent]
        had = None if before is None else OBJECT_OF_KIND.get(before.kind)
        now = state.held
        target = state.facing.ahead(state.pos)
        entry = layout.stations.get(target)
        terrain = None if entry is None else entry[0]
        there = self.lying.get(target)
        if had == now and not (same_swap and terrain is Terrain.COUNTER and there is not None):
            return
        hand: Thing | None = None
        if terrain is Terrain.COUNTER:
            if before is None and now is not None and there is not None:  # picked up
                hand = self.lying.pop(target).at(agent)
            elif before is not None and now is None and there is None:  # put down
                self.lay(target, before)
            elif before is not None and now is not None and there is not None:  # swapped
                hand = self.lying.pop(target).at(agent)
                self.lay(target, before)
        elif terrain in _CRATES and before is None and now is not None:
            hand = self.new(agent, KINDS[now])
        elif terrain is Terrain.GRILL and had == MEAT and now is None:
            self.lay(target, self.new(target, "steak"))
        elif terrain is Terrain.GRILL and had == CLEAN_PLATE and now == STEAK_PLATE and there is not None:
            hand = self.lying.pop(target).at(agent)
        elif terrain is Terrain.BOARD and had == ONION and now is None:
            self.lay(target, self.new(target, "garnish"))
        elif terrain is Terrain.BOARD and had == STEAK_PLATE and now == DISH:
            self.lying.pop(target, None)
        elif terrain is Terrain.SINK and had == DIRTY_PLATE and now is None:
            self.lay(target, self.new(target, "hot_plate"))
        elif terrain is Terrain.SINK and before is None and now == CLEAN_PLATE and there is not None:
            hand = self.lying.pop(target).at(agent)
        if hand is None and now is not None:
            hand = self.new(agent, KINDS[now])
        self.hands[agent] = hand


def reconcile(things: Things, layout: Layout, world: WorldState) -> Things:
    """``things`` made to agree with ``world``: counts taken from it, whatever it lacks dropped, whatever it has
    that ``things`` lack added as new objects (in reading order)."""
    expected: dict[Pos, tuple[str, int | None]] = {pos: (KINDS[obj], None) for pos, obj in world.objects}
    for cells, values, kind in ((layout.grills, world.grills, "steak"), (layout.boards, world.boards, "garnish"),
                                (layout.sinks, world.sinks, "hot_plate")):
        for cell, value in zip(cells, values, strict=True):
            if value is not None:
                expected[cell] = (kind, value)
    next_id = things.next_id
    lying: list[Thing] = []
    for t in things.lying:
        want = expected.get(t.place) if isinstance(t.place, tuple) else None
        if want is not None and want[0] == t.kind:
            lying.append(t if t.state == want[1] else Thing(t.id, t.place, t.kind, want[1]))
    have = {t.place for t in lying}
    for cell in sorted((c for c in expected if c not in have), key=lambda p: (p[1], p[0])):
        lying.append(Thing(next_id, cell, *expected[cell]))
        next_id += 1
    hands: list[Thing | None] = []
    for agent, held, thing in (("robot", world.robot.held, things.robot), ("human", world.human.held, things.human)):
        if held is None:
            hands.append(None)
        elif thing is not None and thing.kind == KINDS[held]:
            hands.append(thing)
        else:
            hands.append(Thing(next_id, agent, KINDS[held]))
            next_id += 1
    return Things(tuple(lying), hands[0], hands[1], next_id)
