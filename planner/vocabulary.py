"""The kitchen's words, each spelled once (docs/domain.md §1): the terrains (their grid characters and their
names), the states a station shows, and the objects a cook can hold.

Every layer above takes its words from here: the layout parser (the characters), the participant's view and the
websocket protocol (the names and states, ``server/protocol/server.py``), the pilot's reading of that view, the
tick summaries and the analysis' columns. The browser spells them in one module of its own
(``static/js/vocabulary.js``), held to this one by ``tests/static/test_client_sources.py``.

A dish is made as: meat → grill; onion → board, chopped; dirty plate → sink, washed, taken out clean;
clean plate takes the steak from the grill (``steak_plate``); the plated steak takes the garnish from
the board (``dish``); the dish is delivered at the serving counter.
"""

from __future__ import annotations

from enum import Enum
from typing import Final, Literal


class Terrain(str, Enum):
    """A cell of the grid, by its character in a layout file."""

    FLOOR = " "
    COUNTER = "X"
    ONION = "O"
    MEAT = "M"
    PLATE = "D"
    GRILL = "P"
    BOARD = "B"
    SINK = "W"
    SERVE = "S"


TerrainName = Literal["floor", "counter", "onion", "meat", "plate", "grill", "board", "sink", "serve"]
"""A terrain's name where it leaves the planner (the view sent to the browser, the admin's scenes)."""

TERRAIN_NAMES: Final[dict[Terrain, TerrainName]] = {
    Terrain.FLOOR: "floor", Terrain.COUNTER: "counter", Terrain.ONION: "onion", Terrain.MEAT: "meat",
    Terrain.PLATE: "plate", Terrain.GRILL: "grill", Terrain.BOARD: "board", Terrain.SINK: "sink",
    Terrain.SERVE: "serve",
}
TERRAIN_OF_NAME: Final[dict[str, Terrain]] = {name: terrain for terrain, name in TERRAIN_NAMES.items()}

STATIONS: Final[tuple[Terrain, ...]] = (
    Terrain.ONION, Terrain.MEAT, Terrain.PLATE, Terrain.GRILL, Terrain.BOARD, Terrain.SINK, Terrain.SERVE,
)
"""The stations every kitchen has at least one of (the dispensers, the grill, board and sink, the serving counter)."""

START_CHARS: Final[dict[str, str]] = {"1": "robot", "2": "human"}
"""The characters of the agents' start cells (floor) in a layout file."""

StationState = Literal["empty", "cooking", "ready", "chopping", "washing", "clean"]
"""What a grill, board or sink shows: empty, working (cooking / chopping / washing) or done (ready / clean)."""

EMPTY: Final[StationState] = "empty"
STATION_STATES: Final[dict[Terrain, tuple[StationState, StationState]]] = {
    Terrain.GRILL: ("cooking", "ready"), Terrain.BOARD: ("chopping", "ready"), Terrain.SINK: ("washing", "clean"),
}
"""For each station with a status: its state while working and once done."""


def station_state(kind: Terrain, count: int | None, done_at: int) -> StationState:
    """The state of a grill, board or sink of ``kind`` whose count is ``count`` (``None``: empty), done at
    ``done_at`` (the cook, chop or wash time)."""
    if count is None:
        return EMPTY
    working, done = STATION_STATES[kind]
    return done if count >= done_at else working


ONION = "onion"
MEAT = "meat"
DIRTY_PLATE = "dirty_plate"
CLEAN_PLATE = "clean_plate"
STEAK_PLATE = "steak_plate"
DISH = "dish"

OBJECTS: Final[tuple[str, ...]] = (ONION, MEAT, DIRTY_PLATE, CLEAN_PLATE, STEAK_PLATE, DISH)
"""Every object an agent can hold or a counter can carry."""
