"""What a simulated participant knows, built only from the frames its browser would receive.

Inputs: ``hello`` (grid size) and each ``state`` message (the cells in view with their terrain, objects and
station statuses; the robot when in view; the own avatar; the HUD). Nothing else: no server state, no
``state.available`` hint (the server's model of the participant), no condition.

- **Which kitchen.** Walls do not move, and the study's kitchens are the researcher's published files: the
  simulated participant recognises its kitchen as the one of the study's layouts (``candidates``) whose
  terrain agrees with every cell seen so far (and with the grid size), as a person does after a first look.
- **The KB.** Each frame is turned into the part of the world it shows (:func:`seen_world`: cells in view,
  robot if in view, own avatar; everything out of view is left as the KB has it) and passed through the
  study's KB rule, ``planner.kb.update_kb``, with the study's FOV angle and KB delay (docs/domain.md §3). A
  change in what the avatar holds is its own doing and enters the KB at once (an own event at the faced cell).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Any

from planner.events import Event, EventKind
from planner.geometry import Direction, Pos
from planner.kb import KnowledgeBase, update_kb
from planner.layout import Layout, Terrain
from planner.state import AgentState, WorldState
from planner.vocabulary import EMPTY, TERRAIN_OF_NAME

OUT_OF_SIGHT: Pos = (-100, -100)
"""Where the seen world puts a robot that is not in view (no cell of any kitchen)."""


class UnknownKitchen(Exception):
    """No layout of the study agrees with what the simulated participant has seen."""


def consistent(layout: Layout, width: int, height: int, seen: Mapping[Pos, str]) -> bool:
    if (layout.width, layout.height) != (width, height):
        return False
    return all(layout.terrain(pos) is TERRAIN_OF_NAME[name] for pos, name in seen.items())


@dataclass(frozen=True, slots=True)
class Perception:
    """The simulated participant's knowledge in one trial: terrain seen, kitchens still possible, its KB."""

    width: int
    height: int
    candidates: tuple[Layout, ...]
    terrain: tuple[tuple[Pos, str], ...] = ()
    kb: KnowledgeBase | None = None
    held: str | None = None
    frames: int = 0
    surprises: int = 0
    """Frames seen, and the sum over frames of the stations and robot cargo in view that disagreed with the KB
    (the KB gap as the simulated participant can measure it: what it finds out it did not know)."""
    tick: int | None = None
    """The tick of the last frame taken in: the KB rule counts ticks in view, so a frame sent again at the same
    tick (the paper's clock tells a refused step with the unchanged state) adds nothing."""

    @property
    def layout(self) -> Layout:
        return self.candidates[0]

    def observe(self, state: Mapping[str, Any], angle: float, kb_delay: int) -> Perception:
        """The knowledge after one ``state`` frame (the same as before for a frame of the same tick again)."""
        if self.kb is not None and state.get("tick") == self.tick:
            return self
        seen = dict(self.terrain)
        seen.update({(c["x"], c["y"]): c["terrain"] for c in state["cells"]})
        candidates = tuple(k for k in self.candidates if consistent(k, self.width, self.height, seen))
        if not candidates:
            raise UnknownKitchen(f"no kitchen of the study has the terrain seen ({len(seen)} cells)")
        layout = candidates[0]
        you = state["you"]
        me = AgentState((you["x"], you["y"]), Direction(you["facing"]), you["held"])
        kb = self.kb if self.kb is not None and len(candidates) == len(self.candidates) else None
        world = seen_world(layout, state, kb)
        if kb is None:
            kb = _first_kb(layout, world)
        own: tuple[Event, ...] = ()
        if self.kb is not None and me.held != self.held:
            own = (Event("human", EventKind.PICK_UP, me.facing.ahead(me.pos), me.held),)
        surprise = _disagreements(layout, state, kb)
        kb = update_kb(kb, layout, world, angle=angle, kb_delay=kb_delay, own_events=own)
        return replace(self, candidates=candidates, terrain=tuple(sorted(seen.items())), kb=kb, held=me.held,
                       frames=self.frames + 1, surprises=self.surprises + surprise, tick=state.get("tick"))

    @property
    def gap_mean(self) -> float:
        return self.surprises / self.frames if self.frames else 0.0


def seen_world(layout: Layout, state: Mapping[str, Any], kb: KnowledgeBase | None) -> WorldState:
    """The world as this frame shows it; what is out of view is taken from ``kb`` (so the KB rule, which reads
    the world only where it is in view, leaves it as it was)."""
    you, robot, hud = state["you"], state["robot"], state["hud"]
    cells: Sequence[Mapping[str, Any]] = state["cells"]
    objects = dict(kb.objects) if kb is not None else {}
    stations = {Terrain.GRILL: list(kb.grills if kb else [None] * len(layout.grills)),
                Terrain.BOARD: list(kb.boards if kb else [None] * len(layout.boards)),
                Terrain.SINK: list(kb.sinks if kb else [None] * len(layout.sinks))}
    for cell in cells:
        pos = (cell["x"], cell["y"])
        entry = layout.stations.get(pos)
        if entry is None:
            continue
        kind, index = entry
        if kind is Terrain.COUNTER:
            if cell["object"] is None:
                objects.pop(pos, None)
            else:
                objects[pos] = cell["object"]
        elif kind in stations and cell["station"] is not None:
            status = cell["station"]
            stations[kind][index] = None if status["state"] == EMPTY else int(status["progress"])
    robot_agent = (AgentState((robot["x"], robot["y"]), Direction(robot["facing"]), robot["held"])
                   if robot is not None else AgentState(OUT_OF_SIGHT, Direction.SOUTH, None))
    return WorldState(human=AgentState((you["x"], you["y"]), Direction(you["facing"]), you["held"]),
                      robot=robot_agent, objects=tuple(sorted(objects.items())),
                      grills=tuple(stations[Terrain.GRILL]), boards=tuple(stations[Terrain.BOARD]),
                      sinks=tuple(stations[Terrain.SINK]), orders_left=int(hud["orders_left"]),
                      tick=int(state["tick"]), score=int(hud["score"]))


def _disagreements(layout: Layout, state: Mapping[str, Any], kb: KnowledgeBase) -> int:
    """Stations in view whose status (empty or not) and a robot in view whose cargo differ from ``kb``."""
    count = 0
    statuses = {Terrain.GRILL: kb.grills, Terrain.BOARD: kb.boards, Terrain.SINK: kb.sinks}
    for cell in state["cells"]:
        entry = layout.stations.get((cell["x"], cell["y"]))
        if entry is not None and entry[0] in statuses and cell["station"] is not None:
            believed = statuses[entry[0]][entry[1]]
            count += int((believed is None) != (cell["station"]["state"] == EMPTY))
    robot = state["robot"]
    if robot is not None and kb.robot is not None:
        count += int(robot["held"] != kb.robot.held)
    return count


def _first_kb(layout: Layout, world: WorldState) -> KnowledgeBase:
    """The KB at the first frame: the setup both players know (empty stations, robot at its start)."""
    start = AgentState(layout.start("robot"), Direction.SOUTH, None)
    return KnowledgeBase(objects=(), grills=(None,) * len(layout.grills), boards=(None,) * len(layout.boards),
                         sinks=(None,) * len(layout.sinks), robot=start)
