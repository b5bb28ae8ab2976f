"""Server-side FOV masking: what the participant's browser may receive at a tick (docs/domain.md §2).

Only cells in the participant's view (``planner.masking.masked``: the one masking function, from the avatar's pose
with the study's angle; the kitchen environment's person sees through it too) are sent, each with its terrain, the
object on it (counters) and its status (grills, boards, sinks); the robot is sent only if its cell is in view.
Everything else about the world never leaves the server.
"""

from __future__ import annotations

from functools import lru_cache

from planner.geometry import Pos
from planner.layout import Layout, Terrain
from planner.masking import masked, station_status
from planner.rules import Rules
from planner.state import AgentState, WorldState
from planner.vocabulary import STATION_STATES, TERRAIN_NAMES, StationState
from server.protocol.server import AgentView, CellView, StationView

_STATUS_KINDS = frozenset(STATION_STATES)


def agent_view(agent: AgentState) -> AgentView:
    return AgentView(x=agent.pos[0], y=agent.pos[1], facing=agent.facing.value, held=agent.held)


def station_view(layout: Layout, world: WorldState, rules: Rules, kind: Terrain, index: int) -> StationView | None:
    """The status of grill / board / sink ``index`` as the participant sees it when it is in view."""
    if kind not in _STATUS_KINDS:
        return None
    counts = world.grills if kind is Terrain.GRILL else world.boards if kind is Terrain.BOARD else world.sinks
    return _station(*station_status(kind, counts[index], rules))


@lru_cache(maxsize=1024)
def _station(state: StationState, progress: int, total: int) -> StationView:
    """Station statuses take few values: one shared (never changed) message part for each."""
    return StationView.model_construct(state=state, progress=progress, total=total)


def drawn_bounds(layout: Layout) -> tuple[int, int, int, int]:
    """``(x, y, width, height)`` of the smallest rectangle holding every floor cell and every station, plus one
    ring of cells around it (kept inside the grid): the part of the kitchen worth drawing. The rest of a
    layout's grid is counters nobody can reach. Reveals only the kitchen's extent, never what is on a cell."""
    cells = [p for p in layout.cells() if layout.terrain(p) is not Terrain.COUNTER]
    xs, ys = [p[0] for p in cells], [p[1] for p in cells]
    x0, y0 = max(min(xs) - 1, 0), max(min(ys) - 1, 0)
    x1, y1 = min(max(xs) + 1, layout.width - 1), min(max(ys) + 1, layout.height - 1)
    return x0, y0, x1 - x0 + 1, y1 - y0 + 1


def visible_world(layout: Layout, world: WorldState, rules: Rules,
                  angle: float) -> tuple[list[CellView], AgentView | None]:
    """The visible cells (reading order) and the robot if it is in view: the participant's masked world
    (:func:`planner.masking.masked`, the one masking function) as message parts.

    Runs for every tick of every trial, so the message part of a cell showing only its terrain is cached and shared
    between messages (they are serialised, never changed). Only objects on counters and station statuses are
    built per tick."""
    seen = masked(layout, world, rules, angle)
    objects = dict(seen.objects) if seen.objects else {}
    stations = {s.pos: s for s in seen.stations}
    bare = _bare_cells(layout, seen.cells)
    cells = []
    for (pos, _), plain in zip(seen.cells, bare, strict=True):
        thing = objects.get(pos)
        station = stations.get(pos)
        if thing is None and station is None:
            cells.append(plain)
        else:
            cells.append(CellView.model_construct(
                x=pos[0], y=pos[1], terrain=plain.terrain, object=thing,
                station=_station(station.state, station.progress, station.total) if station is not None else None))
    return cells, agent_view(seen.other) if seen.other is not None else None


@lru_cache(maxsize=4096)
def _bare_cells(layout: Layout, cells: tuple[tuple[Pos, Terrain], ...]) -> tuple[CellView, ...]:
    """The message parts of ``cells`` showing only their terrain (one tuple per pose's view, cached)."""
    return tuple(CellView.model_construct(x=pos[0], y=pos[1], terrain=TERRAIN_NAMES[terrain], object=None,
                                          station=None) for pos, terrain in cells)
