"""Server-side FOV masking: what the participant's browser may receive at a tick (docs/domain.md §2).

Only cells in the participant's view (``planner.fov.view`` from the avatar's pose, with the study's angle)
are sent, each with its terrain, the object on it (counters) and its status (grills, boards, sinks); the
robot is sent only if its cell is in view. Everything else about the world never leaves the server.
"""

from __future__ import annotations

from functools import lru_cache

from planner.fov import view
from planner.geometry import Direction, Pos
from planner.layout import Layout, Terrain
from planner.rules import Rules
from planner.state import AgentState, WorldState
from planner.vocabulary import STATION_STATES, TERRAIN_NAMES, StationState, station_state
from server.protocol.server import AgentView, CellView, StationView

_STATUS_KINDS = frozenset(STATION_STATES)


def agent_view(agent: AgentState) -> AgentView:
    return AgentView(x=agent.pos[0], y=agent.pos[1], facing=agent.facing.value, held=agent.held)


def station_view(layout: Layout, world: WorldState, rules: Rules, kind: Terrain, index: int) -> StationView | None:
    """The status of grill / board / sink ``index`` as the participant sees it when it is in view."""
    if kind is Terrain.GRILL:
        value, total = world.grills[index], rules.cook_time
    elif kind is Terrain.BOARD:
        value, total = world.boards[index], rules.chop_time
    elif kind is Terrain.SINK:
        value, total = world.sinks[index], rules.wash_time
    else:
        return None
    return _station(station_state(kind, value, total), 0 if value is None else min(value, total), total)


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
    """The visible cells (reading order) and the robot if it is in view.

    Runs for every tick of every trial, so the fixed part is cached: the cells in view of a pose in reading
    order with their terrain (per layout and angle, like ``planner.fov.view``), and the message part of a
    cell showing only its terrain (shared between messages; they are serialised, never changed). Only
    objects on counters and station statuses are built per tick."""
    human = world.human
    seen = view(layout, human.pos, human.facing, angle).cells
    table = _ordered_table(layout, float(angle))
    key = (human.pos, human.facing)
    ordered = table.get(key)
    if ordered is None:
        ordered = table[key] = tuple((pos, _station_entry(layout, pos), _bare_cell(layout, pos))
                                     for pos in sorted(seen, key=lambda p: (p[1], p[0])))
    objects = dict(world.objects) if world.objects else {}
    cells = []
    for pos, entry, bare in ordered:
        thing = objects.get(pos)
        station = station_view(layout, world, rules, entry[0], entry[1]) if entry is not None else None
        if thing is None and station is None:
            cells.append(bare)
        else:
            cells.append(CellView.model_construct(x=pos[0], y=pos[1], terrain=bare.terrain, object=thing,
                                                  station=station))
    robot = agent_view(world.robot) if world.robot.pos in seen else None
    return cells, robot


@lru_cache(maxsize=256)
def _ordered_table(layout: Layout, angle: float) -> dict[tuple[Pos, Direction],
                                                        tuple[tuple[Pos, tuple[Terrain, int] | None, CellView], ...]]:
    return {}


def _station_entry(layout: Layout, pos: Pos) -> tuple[Terrain, int] | None:
    entry = layout.stations.get(pos)
    return entry if entry is not None and entry[0] in _STATUS_KINDS else None


def _bare_cell(layout: Layout, pos: Pos) -> CellView:
    return CellView.model_construct(x=pos[0], y=pos[1], terrain=TERRAIN_NAMES[layout.terrain(pos)], object=None,
                                    station=None)
