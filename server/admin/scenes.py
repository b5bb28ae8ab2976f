"""The experimenter's picture of a trial at one tick: the whole kitchen (nothing masked), the participant's
field of view to overlay on it, and the kitchen as the participant's modelled KB has it.

A scene is split into the fixed ``grid`` (terrain names row by row, sent once per trial) and a ``frame`` per
tick: both agents, the objects on counters, the status of every grill / board / sink (the shape of the
participant protocol's ``StationView``), and ``fov``, the cells in view — computed with the one FOV function
(``planner.fov.view``, docs/domain.md §2) from the human's pose and the study's angle, as the game masks them. The
browser composes grid and frame into the ``state`` shape its kitchen painter already draws.
"""

from __future__ import annotations

from typing import Any, cast

from planner.fov import view
from planner.kb import KnowledgeBase
from planner.layout import Layout
from planner.rules import Rules
from planner.state import AgentState, WorldState
from planner.vocabulary import TERRAIN_NAMES
from server.game.view import station_view


def grid(layout: Layout) -> dict[str, Any]:
    """The fixed part: the kitchen's name, size and terrain name of every cell (rows of columns)."""
    return {"name": layout.name, "width": layout.width, "height": layout.height,
            "terrain": [[TERRAIN_NAMES[layout.terrain((x, y))] for x in range(layout.width)]
                        for y in range(layout.height)]}


def _agent(agent: AgentState | None) -> dict[str, Any] | None:
    if agent is None:
        return None
    return {"x": agent.pos[0], "y": agent.pos[1], "facing": agent.facing.value, "held": agent.held}


def _contents(layout: Layout, statuses: WorldState | KnowledgeBase, rules: Rules) -> dict[str, Any]:
    """Objects on counters and the status of every grill, board and sink, in reading order."""
    stations = []
    for pos in sorted(layout.stations, key=lambda p: (p[1], p[0])):
        kind, index = layout.stations[pos]
        status = station_view(layout, cast(WorldState, statuses), rules, kind, index)
        if status is not None:
            stations.append({"x": pos[0], "y": pos[1], **status.model_dump()})
    objects = [{"x": p[0], "y": p[1], "object": o} for p, o in sorted(statuses.objects, key=lambda i: (i[0][1],
                                                                                                       i[0][0]))]
    return {"objects": objects, "stations": stations}


def fov_cells(layout: Layout, world: WorldState, angle: float) -> list[list[int]]:
    """The cells in the participant's view (reading order)."""
    cells = view(layout, world.human.pos, world.human.facing, angle).cells
    return [[x, y] for x, y in sorted(cells, key=lambda p: (p[1], p[0]))]


def frame(layout: Layout, world: WorldState, rules: Rules, angle: float) -> dict[str, Any]:
    """The whole world at one tick, with the participant's field of view."""
    return {"tick": world.tick, "human": _agent(world.human), "robot": _agent(world.robot),
            **_contents(layout, world, rules), "fov": fov_cells(layout, world, angle),
            "orders_left": world.orders_left, "score": world.score}


def kb_frame(layout: Layout, kb: KnowledgeBase, rules: Rules) -> dict[str, Any]:
    """The kitchen as the participant's modelled KB has it: believed objects and station statuses, and the
    robot where it was last seen (``None`` if never)."""
    return {"robot": _agent(kb.robot), **_contents(layout, kb, rules)}
