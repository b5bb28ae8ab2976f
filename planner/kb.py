"""The human's knowledge base (KB): what the person believes about the world (docs/domain.md §3, paper §III-B).

Contents: the status of each grill, board and sink, the objects on counters, and the robot's last acknowledged
pose and held object. They are updated once per tick, after the world has stepped, by the acknowledgement rule
the reference implementation ran (:mod:`planner.kb_rule`, on the object identities of :mod:`planner.kb_things`):

* Everything in view counts its consecutive ticks in view, capped at ``kb_delay``; an object keeps its count while
  it is carried or worked on in view, the robot keeps its count whatever its hands do. At ``kb_delay`` the KB
  follows it every tick (where it is, its cook, chop or wash count; the robot's pose and hands), so a change of
  hands of a robot watched long enough is acknowledged at once.
* Out of view, the last acknowledged value persists. An object whose remembered place is in view without it is
  forgotten once that place has been in view ``kb_delay`` ticks (not necessarily consecutive).
* What the person holds, and what they make of it, enters the KB at once.

``kb_delay = 0`` with a 360° FOV gives a KB that follows the world (docs/domain.md §3 names the reference's
quirks that can still set it apart for a tick).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

from planner.events import Event
from planner.fov import view
from planner.geometry import Pos
from planner.kb_json import tracking_from_dict, tracking_to_dict
from planner.kb_rule import RobotSnap, Snap, Tracking, acknowledge
from planner.kb_things import OBJECT_OF_KIND, advance, first_things, kind_at
from planner.layout import Layout, Terrain
from planner.objects import OBJECTS
from planner.state import AgentState, WorldState

ROBOT_KEY: Pos = (-1, -1)
"""The key of the robot's entry in :attr:`KnowledgeBase.streaks`."""


@dataclass(frozen=True, slots=True)
class KnowledgeBase:
    """Believed station statuses (same encoding as :class:`WorldState`), counter objects and robot, and the
    acknowledgement rule's memory (``tracking``; ``None`` for a KB made from its contents alone, which the next
    update takes up as it stands)."""

    objects: tuple[tuple[Pos, str], ...]
    grills: tuple[int | None, ...]
    boards: tuple[int | None, ...]
    sinks: tuple[int | None, ...]
    robot: AgentState | None
    tracking: Tracking | None = None

    def object_at(self, pos: Pos) -> str | None:
        for where, obj in self.objects:
            if where == pos:
                return obj
        return None

    @property
    def streaks(self) -> tuple[tuple[Pos, object, int], ...]:
        """The robot's count of consecutive ticks in view, as ``(ROBOT_KEY, what it holds, count)``, while the
        person sees it (empty otherwise)."""
        if self.tracking is None or self.tracking.robot is None:
            return ()
        snap, count = self.tracking.robot
        return ((ROBOT_KEY, snap.state.held, count),)

    def to_dict(self) -> dict[str, object]:
        return {
            "objects": [{"pos": list(p), "obj": o} for p, o in self.objects],
            "grills": list(self.grills), "boards": list(self.boards), "sinks": list(self.sinks),
            "robot": None if self.robot is None else self.robot.to_dict(),
            "tracking": None if self.tracking is None else tracking_to_dict(self.tracking),
        }

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> KnowledgeBase:
        """The inverse of :meth:`to_dict` (resuming a trial keeps the rule's memory; a KB stored before the rule
        had one is read without it); ``ValueError`` on unknown objects or a malformed memory."""
        objects = []
        for item in data["objects"]:
            if item["obj"] not in OBJECTS:
                raise ValueError(f"unknown object {item['obj']!r}")
            objects.append(((int(item["pos"][0]), int(item["pos"][1])), str(item["obj"])))
        robot = data.get("robot")
        tracking = data.get("tracking")
        try:
            memory = None if tracking is None else tracking_from_dict(tracking)
        except (KeyError, TypeError, IndexError) as exc:
            raise ValueError(f"malformed KB tracking: {exc}") from exc
        return cls(objects=tuple(sorted(objects)), grills=tuple(_count(v) for v in data["grills"]),
                   boards=tuple(_count(v) for v in data["boards"]), sinks=tuple(_count(v) for v in data["sinks"]),
                   robot=None if robot is None else AgentState.from_dict(robot), tracking=memory)


def _count(value: Any) -> int | None:
    return None if value is None else int(value)


def initial_kb(state: WorldState) -> KnowledgeBase:
    """The KB at the start of a trial: what lies in the kitchen (nothing, in a fresh one) and the robot at its
    start (both know the setup). Needs no layout: the start's objects are taken as they lie."""
    return KnowledgeBase(objects=state.objects, grills=state.grills, boards=state.boards, sinks=state.sinks,
                         robot=state.robot)


def omniscient_kb(state: WorldState) -> KnowledgeBase:
    """A KB equal to the world (FOV 360°, delay 0)."""
    return initial_kb(state)


def update_kb(kb: KnowledgeBase, layout: Layout, world: WorldState, *, angle: float, kb_delay: int,
              own_events: Iterable[Event] = (), pose: AgentState | None = None) -> KnowledgeBase:
    """The KB after one tick, given the world after the step and the human's events of that step.

    ``pose`` is the viewer (defaults to ``world.human``); its FOV decides what is in view. The person's own
    interactions are read from their hands (:mod:`planner.kb_things`); ``own_events`` tell a swap of two equal
    objects apart from standing still.
    """
    viewer = pose or world.human
    seen = view(layout, viewer.pos, viewer.facing, angle).cells
    if kb.tracking is None:
        memory = _taken_up(kb, layout, world)
        things = memory.things
    else:
        memory = kb.tracking
        things = advance(memory.things, layout, world, own_events)
    memory, robot = acknowledge(memory, things, world.human, world.robot, seen, kb_delay)
    believed_robot = kb.robot if robot is None else robot
    if kb.tracking is not None and memory.believed == kb.tracking.believed:
        # The same believed objects, so the same contents (a KB with a memory holds its contents: it was made
        # here, or restored from its own record): most ticks.
        return KnowledgeBase(kb.objects, kb.grills, kb.boards, kb.sinks, believed_robot, memory)
    return _contents(memory, layout, believed_robot)


def _taken_up(kb: KnowledgeBase, layout: Layout, world: WorldState) -> Tracking:
    """The rule's memory for a KB known only by its contents: the world's objects get identities; each believed
    object takes the identity of the world's object of its kind at its place, if any, and is remembered there
    as if it had just left the view (so it is checked once its place is seen); the robot likewise."""
    things = first_things(layout, world)
    at = {t.place: t for t in things.lying}
    next_id = things.next_id
    believed: list[tuple[int, Snap]] = []
    for cell, kind, state in _believed_contents(kb, layout):
        match = at.get(cell)
        if match is not None and match.kind == kind:
            ident = match.id
        else:
            ident, next_id = next_id, next_id + 1
        believed.append((ident, Snap(cell, kind, state)))
    things = type(things)(things.lying, things.robot, things.human, next_id)
    robot = None if kb.robot is None else RobotSnap(kb.robot, None, None)
    return Tracking(things=things, untrack=tuple(believed), robot_untrack=robot, believed=tuple(believed))


def _believed_contents(kb: KnowledgeBase, layout: Layout) -> list[tuple[Pos, str, int | None]]:
    found: list[tuple[Pos, str, int | None]] = []
    for pos, obj in kb.objects:
        kind = kind_at(layout, pos, obj)
        if kind is not None:
            found.append((pos, kind, None))
    for cells, values in ((layout.grills, kb.grills), (layout.boards, kb.boards), (layout.sinks, kb.sinks)):
        for cell, value in zip(cells, values, strict=True):
            if value is not None:
                found.append((cell, kind_at(layout, cell, None) or "", value))
    return found


def _contents(memory: Tracking, layout: Layout, robot: AgentState | None) -> KnowledgeBase:
    """The KB's contents from the objects the rule believes: those on counters, and per station the largest
    count believed there (a station holds one object; the rule can believe a second one for a tick)."""
    counters: dict[Pos, str] = {}
    stations: dict[Pos, int] = {}
    for _ident, snap in memory.believed:
        entry = layout.stations.get(snap.cell)
        if entry is None:
            continue
        if entry[0] is Terrain.COUNTER:
            obj = OBJECT_OF_KIND.get(snap.kind)
            if obj is not None:
                counters[snap.cell] = obj
        elif snap.state is not None and kind_at(layout, snap.cell, None) == snap.kind:
            stations[snap.cell] = max(snap.state, stations.get(snap.cell, snap.state))
    return KnowledgeBase(
        objects=tuple(sorted(counters.items())),
        grills=tuple(stations.get(c) for c in layout.grills),
        boards=tuple(stations.get(c) for c in layout.boards),
        sinks=tuple(stations.get(c) for c in layout.sinks),
        robot=robot, tracking=memory,
    )
