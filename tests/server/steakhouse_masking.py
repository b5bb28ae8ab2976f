"""The masking property, checked on what a participant's websocket received: every ``state`` shows exactly
the cells in the participant's view at that tick (recomputed with ``planner.fov.view`` from the pose in the
message) with the stored world's objects and stations there, the robot only when its cell is in view, and
no other message carries a position."""

from __future__ import annotations

from typing import Any

from planner.fov import view
from planner.geometry import Direction
from planner.state import WorldState
from server.game.view import drawn_bounds, station_view
from store import trials
from store.tables import TrialRow
from study_config import load_layout


def coordinates(value: Any, path: str = "") -> list[tuple[str, int, int]]:
    """Every ``{x, y}`` pair anywhere in a message, with where it was found."""
    found = []
    if isinstance(value, dict):
        if "x" in value and "y" in value:
            found.append((path, value["x"], value["y"]))
        for key, item in value.items():
            found += coordinates(item, f"{path}.{key}")
    elif isinstance(value, list):
        for i, item in enumerate(value):
            found += coordinates(item, f"{path}[{i}]")
    return found


def check_masked(server: Any, trial_id: int, messages: list[dict[str, Any]], study_id: str = "tiny") -> tuple[int, int]:
    """Assert the property over ``messages`` (starting with ``hello``) of ``trial_id``, comparing with the
    ticks ``server`` stored. Returns how often the robot was shown and how often hidden."""
    with server.services.store.transaction() as session:
        row = session.get(TrialRow, trial_id)
        worlds = {t.tick: WorldState.from_dict(t.world_state) for t in trials.ticks(session, trial_id)}
        worlds[0] = WorldState.from_dict(row.initial_state)
        layout = load_layout(row.kitchen)
    hello = messages[0]
    assert hello["type"] == "hello" and "cells" not in hello and not coordinates(hello)
    bounds = hello["bounds"]  # the kitchen's extent from its terrain only (the same for every trial in it)
    assert (bounds["left"], bounds["top"], bounds["width"], bounds["height"]) == drawn_bounds(layout)
    rules = server.services.catalog.get(study_id).rules
    shown = hidden = 0
    for message in messages:
        if message["type"] != "state":
            assert not coordinates(message), f"{message['type']} carries coordinates"
            continue
        you = message["you"]
        pose = ((you["x"], you["y"]), Direction(you["facing"]))
        seen = view(layout, pose[0], pose[1], hello["fov_angle"]).cells
        for where, x, y in coordinates(message):
            assert (x, y) in seen, f"trial {trial_id} tick {message['tick']}: {where} at {(x, y)} is out of view"
        world = worlds[message["tick"]]
        assert (world.human.pos, world.human.facing) == pose
        assert {(c["x"], c["y"]) for c in message["cells"]} == seen
        objects = dict(world.objects)
        for cell in message["cells"]:
            pos = (cell["x"], cell["y"])
            assert cell["object"] == objects.get(pos)
            entry = layout.stations.get(pos)
            expected = station_view(layout, world, rules, *entry) if entry else None
            assert cell["station"] == (expected.model_dump() if expected else None)
        if world.robot.pos in seen:
            shown += 1
            robot = message["robot"]
            assert (robot["x"], robot["y"], robot["facing"], robot["held"]) == (
                *world.robot.pos, world.robot.facing.value, world.robot.held)
        else:
            hidden += 1
            assert message["robot"] is None
    return shown, hidden
