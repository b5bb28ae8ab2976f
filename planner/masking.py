"""What one cook may know of the world at a tick: the one masking function (docs/domain.md §2).

:func:`masked` takes the true world and gives what is in a cook's view (``planner.fov.view`` from their pose,
with the trial's angle): the cells in view in reading order with their terrain, the objects lying on them, the
status of the grills, boards and sinks among them, and the other cook if their cell is in view; the cook's own
pose and hands, and the HUD's numbers (tick, orders left, score), are always known. Everything else is not there.

Two renderings read it: the participant's per-tick frame (``server/game/view.py``: the only world the browser
receives) and the kitchen environment's observation for the person (``planner/env/observation.py``); so the
environment trains a robot against exactly what a participant sees.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

from planner.fov import view
from planner.geometry import Direction, Pos
from planner.layout import Layout, Terrain
from planner.rules import Rules
from planner.state import AgentState, WorldState
from planner.vocabulary import StationState, station_state


@dataclass(frozen=True, slots=True)
class SeenStation:
    """A grill, board or sink in view: its cell, kind, index and what it shows (``state``; ``progress`` cook ticks,
    chop or wash presses so far, at most ``total``, the number needed)."""

    pos: Pos
    kind: Terrain
    index: int
    state: StationState
    progress: int
    total: int


@dataclass(frozen=True, slots=True)
class Masked:
    """One cook's masked world (see the module docstring). ``cells`` is shared between calls (cached per pose)."""

    me: AgentState
    other: AgentState | None
    cells: tuple[tuple[Pos, Terrain], ...]
    objects: tuple[tuple[Pos, str], ...]
    stations: tuple[SeenStation, ...]
    tick: int
    orders_left: int
    score: int


def station_status(kind: Terrain, count: int | None, rules: Rules) -> tuple[StationState, int, int]:
    """``(state, progress, total)`` of a grill, board or sink of ``kind`` whose count is ``count``."""
    total = rules.cook_time if kind is Terrain.GRILL else rules.chop_time if kind is Terrain.BOARD else rules.wash_time
    return station_state(kind, count, total), 0 if count is None else min(count, total), total


def masked(layout: Layout, world: WorldState, rules: Rules, angle: float, me: str = "human") -> Masked:
    """What the cook ``me`` (``"human"`` or ``"robot"``) may know of ``world`` with a field of view of ``angle``
    degrees (360: everything)."""
    agent = world.agent(me)
    other = world.robot if me == "human" else world.human
    seen = view(layout, agent.pos, agent.facing, angle)
    statuses = {Terrain.GRILL: world.grills, Terrain.BOARD: world.boards, Terrain.SINK: world.sinks}
    stations = tuple(SeenStation(pos, kind, index, *station_status(kind, statuses[kind][index], rules))
                     for pos, kind, index in seen.stations)
    objects = tuple(item for item in world.objects if item[0] in seen.cells) if world.objects else ()
    return Masked(me=agent, other=other if other.pos in seen.cells else None,
                  cells=ordered_cells(layout, agent.pos, agent.facing, float(angle)), objects=objects,
                  stations=stations, tick=world.tick, orders_left=world.orders_left, score=world.score)


def ordered_cells(layout: Layout, pos: Pos, facing: Direction, angle: float) -> tuple[tuple[Pos, Terrain], ...]:
    """The cells in view of a pose in reading order, with their terrain (cached per layout, angle and pose)."""
    table = _ordered_table(layout, float(angle))
    key = (pos, facing)
    found = table.get(key)
    if found is None:
        cells = view(layout, pos, facing, angle).cells
        found = table[key] = tuple((c, layout.terrain(c)) for c in sorted(cells, key=lambda p: (p[1], p[0])))
    return found


@lru_cache(maxsize=256)
def _ordered_table(layout: Layout, angle: float) -> dict[tuple[Pos, Direction], tuple[tuple[Pos, Terrain], ...]]:
    return {}
