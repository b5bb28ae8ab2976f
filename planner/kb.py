"""The human's knowledge base (KB): what the person believes about the world (docs/domain.md §3, paper §III-B).

Contents: the status of each grill, board and sink, the objects on counters, and the robot's last
acknowledged pose and held object. The rules, applied once per tick after the world has stepped:

* Every tracked cell (counter, grill, board, sink) and the robot carry a *streak*: the number of
  consecutive ticks they have been in view with the same occupant (the object on a counter, whether a
  station holds anything, what the robot holds). When the streak reaches ``kb_delay`` the KB takes the
  world's value, and while it stays in view the KB stays current (cook, chop and wash counts included).
* Out of view, the last acknowledged value persists. A changed occupant restarts the streak, so an object
  seen missing is removed once its place has been in view ``kb_delay`` ticks without it.
* What the human does itself (pick up, put down, chop, wash, …) enters the KB at once.
* When the robot is acknowledged holding an object the KB places elsewhere, that object is removed from
  its old place (the nearest such counter to the robot; for a clean plate the sink, a plated steak the
  grill, a dish the board).

``kb_delay = 0`` with a 360° FOV gives an omniscient human whose KB always equals the world.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

from planner.events import Event
from planner.fov import view
from planner.geometry import Pos, manhattan
from planner.layout import Layout, Terrain
from planner.objects import CLEAN_PLATE, DISH, OBJECTS, STEAK_PLATE
from planner.state import AgentState, WorldState

ROBOT_KEY: Pos = (-1, -1)
_TRACKED_KINDS = (Terrain.COUNTER, Terrain.GRILL, Terrain.BOARD, Terrain.SINK)
_NO_OBJECTS: dict[Pos, str] = {}


@dataclass(frozen=True, slots=True)
class KnowledgeBase:
    """Believed station statuses (same encoding as :class:`WorldState`), counter objects and robot.

    ``streaks`` holds ``(key, occupant, count)`` for what was in view last tick and may still change the KB:
    counters whose content disagrees with the KB, the stations, and the robot (``ROBOT_KEY``).
    """

    objects: tuple[tuple[Pos, str], ...]
    grills: tuple[int | None, ...]
    boards: tuple[int | None, ...]
    sinks: tuple[int | None, ...]
    robot: AgentState | None
    streaks: tuple[tuple[Pos, object, int], ...] = ()

    def object_at(self, pos: Pos) -> str | None:
        for where, obj in self.objects:
            if where == pos:
                return obj
        return None

    def to_dict(self) -> dict[str, object]:
        return {
            "objects": [{"pos": list(p), "obj": o} for p, o in self.objects],
            "grills": list(self.grills), "boards": list(self.boards), "sinks": list(self.sinks),
            "robot": None if self.robot is None else self.robot.to_dict(),
            "streaks": [[list(k), occ, n] for k, occ, n in self.streaks],
        }

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> KnowledgeBase:
        """The inverse of :meth:`to_dict` (resuming a trial keeps the streaks); ``ValueError`` on unknown
        objects."""
        objects = []
        for item in data["objects"]:
            if item["obj"] not in OBJECTS:
                raise ValueError(f"unknown object {item['obj']!r}")
            objects.append(((int(item["pos"][0]), int(item["pos"][1])), str(item["obj"])))
        streaks = []
        for key, occupant, count in data.get("streaks", []):
            pos = (int(key[0]), int(key[1]))
            streaks.append((ROBOT_KEY if pos == ROBOT_KEY else pos, occupant, int(count)))
        robot = data.get("robot")
        return cls(objects=tuple(sorted(objects)), grills=tuple(_count(v) for v in data["grills"]),
                   boards=tuple(_count(v) for v in data["boards"]), sinks=tuple(_count(v) for v in data["sinks"]),
                   robot=None if robot is None else AgentState.from_dict(robot), streaks=tuple(streaks))


def _count(value: Any) -> int | None:
    return None if value is None else int(value)


def initial_kb(state: WorldState) -> KnowledgeBase:
    """The KB at the start of a trial: the kitchen is empty and the robot at its start (both know the setup)."""
    return KnowledgeBase(objects=state.objects, grills=state.grills, boards=state.boards,
                         sinks=state.sinks, robot=state.robot)


def omniscient_kb(state: WorldState) -> KnowledgeBase:
    """A KB equal to the world (FOV 360°, delay 0)."""
    return initial_kb(state)


class _Working:
    """Mutable copies of the KB's parts, made only when a part changes."""

    __slots__ = ("kb", "layout", "objects", "robot", "stations")

    def __init__(self, kb: KnowledgeBase, layout: Layout) -> None:
        self.kb, self.layout = kb, layout
        self.objects: dict[Pos, str] | None = None
        self.stations: dict[Terrain, list[int | None]] = {}
        self.robot = kb.robot

    def counters(self) -> dict[Pos, str]:
        if self.objects is None:
            self.objects = dict(self.kb.objects)
        return self.objects

    def station_list(self, kind: Terrain) -> list[int | None]:
        found = self.stations.get(kind)
        if found is None:
            found = self.stations[kind] = list(_statuses(self.kb, kind))
        return found

    def set_counter(self, cell: Pos, obj: str | None) -> None:
        counters = self.counters()
        if obj is None:
            counters.pop(cell, None)
        else:
            counters[cell] = obj

    def copy_cell(self, cell: Pos, world: WorldState, world_objects: dict[Pos, str]) -> None:
        kind, i = self.layout.stations[cell]
        if kind is Terrain.COUNTER:
            self.set_counter(cell, world_objects.get(cell))
        else:
            value = _statuses(world, kind)[i]
            if _statuses(self.kb, kind)[i] != value or kind in self.stations:
                self.station_list(kind)[i] = value

    def build(self, streaks: list[tuple[Pos, object, int]]) -> KnowledgeBase:
        kb = self.kb
        return KnowledgeBase(
            objects=kb.objects if self.objects is None else tuple(sorted(self.objects.items())),
            grills=_frozen(self.stations, Terrain.GRILL, kb.grills),
            boards=_frozen(self.stations, Terrain.BOARD, kb.boards),
            sinks=_frozen(self.stations, Terrain.SINK, kb.sinks),
            robot=self.robot, streaks=tuple(streaks),
        )


def _frozen(changed: dict[Terrain, list[int | None]], kind: Terrain,
            original: tuple[int | None, ...]) -> tuple[int | None, ...]:
    values = changed.get(kind)
    return original if values is None else tuple(values)


def _statuses(source: WorldState | KnowledgeBase, kind: Terrain) -> tuple[int | None, ...]:
    if kind is Terrain.GRILL:
        return source.grills
    if kind is Terrain.BOARD:
        return source.boards
    return source.sinks


def update_kb(kb: KnowledgeBase, layout: Layout, world: WorldState, *, angle: float, kb_delay: int,
              own_events: Iterable[Event] = (), pose: AgentState | None = None) -> KnowledgeBase:
    """The KB after one tick, given the world after the step and the human's events of that step.

    ``pose`` is the viewer (defaults to ``world.human``); its FOV decides what is in view.

    Only counters whose world content differs from the KB need a streak (a counter that agrees with
    the KB gains nothing from acknowledgement, and any change restarts its count anyway), so the work per
    tick is proportional to the objects in the kitchen, not to the cells in view.
    """
    viewer = pose or world.human
    seen = view(layout, viewer.pos, viewer.facing, angle)
    in_view = seen.cells
    w = _Working(kb, layout)
    world_objects: dict[Pos, str] | None = None
    previous = {key: (occ, n) for key, occ, n in kb.streaks}
    streaks: list[tuple[Pos, object, int]] = []
    own_cells = set()
    for event in own_events:
        entry = layout.stations.get(event.pos)
        if entry is not None and entry[0] in _TRACKED_KINDS:
            if world_objects is None:
                world_objects = dict(world.objects)
            own_cells.add(event.pos)
            w.copy_cell(event.pos, world, world_objects)
    if own_cells or world.objects != kb.objects:  # else every counter agrees with the KB: no streak to keep
        if world_objects is None:
            world_objects = dict(world.objects)
        kb_objects = w.counters() if own_cells else dict(kb.objects)
        for cell in world_objects.keys() | kb_objects.keys():
            if cell not in in_view:
                continue
            occ = world_objects.get(cell)
            if occ == kb_objects.get(cell):
                continue
            prev = previous.get(cell)
            count = prev[1] + 1 if prev is not None and prev[0] == occ else 1
            if count >= kb_delay:
                w.set_counter(cell, occ)
            else:
                streaks.append((cell, occ, count))
    for cell, kind, i in seen.stations:
        value = _statuses(world, kind)[i]
        occupied = value is not None
        prev = previous.get(cell)
        count = prev[1] + 1 if prev is not None and prev[0] == occupied else 1
        if cell in own_cells:
            count = max(count, kb_delay)
        streaks.append((cell, occupied, count))
        if count >= kb_delay:
            w.copy_cell(cell, world, _NO_OBJECTS)  # a grill, board or sink: no counter read
    robot = world.robot
    if robot.pos in in_view:
        prev = previous.get(ROBOT_KEY)
        count = prev[1] + 1 if prev is not None and prev[0] == robot.held else 1
        streaks.append((ROBOT_KEY, robot.held, count))
        if count >= kb_delay:
            before = w.robot.held if w.robot is not None else None
            w.robot = robot
            if robot.held is not None and robot.held != before:
                _remove_elsewhere(w, robot, in_view)
    return w.build(streaks)


_STATION_SOURCE = {CLEAN_PLATE: Terrain.SINK, STEAK_PLATE: Terrain.GRILL, DISH: Terrain.BOARD}


def _remove_elsewhere(w: _Working, robot: AgentState, in_view: frozenset[Pos]) -> None:
    """The robot holds what the KB believed was elsewhere: take it from its believed place."""
    held = robot.held
    source = _STATION_SOURCE.get(held)  # type: ignore[arg-type]
    if source is not None:
        cells = {Terrain.SINK: w.layout.sinks, Terrain.GRILL: w.layout.grills,
                 Terrain.BOARD: w.layout.boards}[source]
        statuses = w.station_list(source)
        candidates = [i for i, s in enumerate(statuses) if s is not None and cells[i] not in in_view]
        if candidates:
            nearest = min(candidates, key=lambda i: manhattan(cells[i], robot.pos))
            statuses[nearest] = None
        return
    counters = w.counters()
    places = [p for p, obj in counters.items() if obj == held and p not in in_view]
    if places:
        del counters[min(places, key=lambda p: manhattan(p, robot.pos))]
