"""What a cook observes, as arrays (numpy only): the rendering of :func:`planner.masking.masked` that the kitchen
environment hands its agents (docs/robots.md, "The environment").

``grid`` is ``uint8`` of shape ``(len(CHANNELS), height, width)``, one plane per channel of :data:`CHANNELS`, zero
wherever the cook does not see: ``in_view``; one plane per terrain (``terrain_floor`` … ``terrain_serve``); one per
object lying on a counter (``object_onion`` …); ``station_progress`` (cook ticks, chop or wash presses, at most the
number needed) and ``station_state`` (0 empty, 1 working, 2 done) of the grills, boards and sinks; ``me`` (1 on the
cook's cell), ``me_facing`` (1 + index in north, south, east, west) and ``me_held`` (1 + index of the object in
``planner.vocabulary.OBJECTS``, 0 for empty hands) on the cook's cell; the same three for the ``other`` cook, on
their cell when it is in view. ``hud`` is ``int32`` ``(tick, orders_left, score)``, what the participant's HUD
shows. The person sees with the trial's field of view; the robot with 360° (everything).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from planner.geometry import DIRECTIONS, Direction, Pos
from planner.layout import Layout, Terrain
from planner.masking import Masked, masked, ordered_cells
from planner.rules import Rules
from planner.state import AgentState, WorldState
from planner.vocabulary import OBJECTS, TERRAIN_NAMES

TERRAINS: tuple[Terrain, ...] = tuple(Terrain)
CHANNELS: tuple[str, ...] = (
    "in_view", *(f"terrain_{TERRAIN_NAMES[t]}" for t in TERRAINS), *(f"object_{o}" for o in OBJECTS),
    "station_progress", "station_state", "me", "me_facing", "me_held", "other", "other_facing", "other_held",
)
HUD: tuple[str, ...] = ("tick", "orders_left", "score")
_AT = {name: i for i, name in enumerate(CHANNELS)}
_OBJECT = {o: _AT[f"object_{o}"] for o in OBJECTS}
_FACING = {d: i + 1 for i, d in enumerate(DIRECTIONS)}
_HELD = {o: i + 1 for i, o in enumerate(OBJECTS)}
_STATE = {"empty": 0, "cooking": 1, "chopping": 1, "washing": 1, "ready": 2, "clean": 2}


def observe(layout: Layout, world: WorldState, rules: Rules, angle: float, me: str) -> dict[str, np.ndarray]:
    """The observation of cook ``me`` (``"human"`` or ``"robot"``) with a field of view of ``angle`` degrees."""
    return encode(layout, masked(layout, world, rules, angle, me), angle)


def encode(layout: Layout, seen: Masked, angle: float) -> dict[str, np.ndarray]:
    """:func:`observe` of a masked world."""
    grid = _view_planes(layout, float(angle), seen.me.pos, seen.me.facing).copy()
    for (x, y), obj in seen.objects:
        grid[_OBJECT[obj], y, x] = 1
    for station in seen.stations:
        x, y = station.pos
        grid[_AT["station_progress"], y, x] = min(station.progress, 255)
        grid[_AT["station_state"], y, x] = _STATE[station.state]
    _agent(grid, "me", seen.me)
    if seen.other is not None:
        _agent(grid, "other", seen.other)
    hud = np.array((seen.tick, seen.orders_left, seen.score), dtype=np.int32)
    return {"grid": grid, "hud": hud}


def _agent(grid: np.ndarray, who: str, agent: AgentState) -> None:
    x, y = agent.pos
    grid[_AT[who], y, x] = 1
    grid[_AT[f"{who}_facing"], y, x] = _FACING[agent.facing]
    grid[_AT[f"{who}_held"], y, x] = _HELD[agent.held] if agent.held is not None else 0


def _view_planes(layout: Layout, angle: float, pos: Pos, facing: Direction) -> np.ndarray:
    """The planes that depend on the pose alone (``in_view`` and the terrains in view), cached per pose."""
    table = _planes_table(layout, angle)
    key = (pos, facing)
    found = table.get(key)
    if found is None:
        found = np.zeros((len(CHANNELS), layout.height, layout.width), dtype=np.uint8)
        for (x, y), terrain in ordered_cells(layout, pos, facing, angle):
            found[_AT["in_view"], y, x] = 1
            found[_AT[f"terrain_{TERRAIN_NAMES[terrain]}"], y, x] = 1
        found.setflags(write=False)
        table[key] = found
    return found


@lru_cache(maxsize=256)
def _planes_table(layout: Layout, angle: float) -> dict[tuple[Pos, Direction], np.ndarray]:
    return {}
