"""The masking property: over whole trials with a moving participant and a moving robot, no server message
ever contains a cell, object, station state or robot position outside the participant's FOV at that tick.

The FOV is recomputed independently from the avatar's pose in each message with ``planner.fov.view``; the
messages are also compared with the stored world of the same tick, so what is sent is exactly the visible
part of the world (nothing missing, nothing added).
"""

from __future__ import annotations

import asyncio
import random
from typing import Any

import pytest
from steakhouse_test_robots import simulated_partner
from steakhouse_testing import Player

from planner.fov import view
from planner.geometry import Direction
from planner.state import WorldState
from server.game.view import station_view
from server.store import trials
from study_config import load_layout

MOVES = ("up", "down", "left", "right")


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


async def play_moving(server, seed: int) -> tuple[dict[str, Any], list[dict[str, Any]]]:
    rng = random.Random(seed)
    player = Player(server.url)
    await player.ready()
    sock = await player.socket()
    hello = await sock.recv()
    while True:
        message = await sock.recv()
        if message["type"] == "trial_end":
            break
        if message["type"] != "state" or message["hud"]["ticks_left"] == 0:
            continue
        if rng.random() < 0.25:
            await sock.send("interrupt", action=rng.choice(MOVES))
        elif message["subtask"] is None and message["available"]:
            await sock.send("select_subtask", subtask=rng.choice(message["available"]))
    await sock.close()
    await player.close()
    return hello, sock.received


@pytest.mark.parametrize("kitchen", ["mid_2", "none_3"])
def test_no_message_leaves_the_participants_field_of_view(live_server, study_file, kitchen):
    study = study_file(kitchens=[kitchen], world={"orders": 2, "horizon": 90, "kb_delay": 3, "fov_angle": 120})
    server = live_server([study], robot_factory=simulated_partner)
    hello, received = asyncio.run(play_moving(server, seed=7))
    layout = load_layout(kitchen)
    assert set(hello) >= {"width", "height"} and not coordinates(hello) and "cells" not in hello
    with server.services.store.transaction() as session:
        worlds = {t.tick: WorldState.from_dict(t.world_state) for t in trials.ticks(session, hello["trial"]["id"])}
    worlds[0] = WorldState.from_dict(_initial(server, hello["trial"]["id"]))
    states = [m for m in received if m["type"] == "state"]
    assert len(states) >= 60
    robot_seen = robot_hidden = 0
    for message in received:
        if message["type"] != "state":
            assert not coordinates(message), f"{message['type']} carries coordinates"
            continue
        you = message["you"]
        pose = ((you["x"], you["y"]), Direction(you["facing"]))
        seen = view(layout, pose[0], pose[1], hello["fov_angle"]).cells
        for where, x, y in coordinates(message):
            assert (x, y) in seen, f"tick {message['tick']}: {where} at {(x, y)} is out of view"
        world = worlds[message["tick"]]
        assert (world.human.pos, world.human.facing) == pose
        assert {(c["x"], c["y"]) for c in message["cells"]} == seen
        objects = dict(world.objects)
        for cell in message["cells"]:
            pos = (cell["x"], cell["y"])
            assert cell["object"] == objects.get(pos)
            entry = layout.stations.get(pos)
            expected = station_view(layout, world, server.services.catalog.get("tiny").rules, *entry) if entry else None
            assert cell["station"] == (expected.model_dump() if expected else None)
        if world.robot.pos in seen:
            robot_seen += 1
            robot = message["robot"]
            assert (robot["x"], robot["y"], robot["facing"], robot["held"]) == (
                *world.robot.pos, world.robot.facing.value, world.robot.held)
        else:
            robot_hidden += 1
            assert message["robot"] is None
    assert robot_seen > 0 and robot_hidden > 0, "the trial must show and hide the robot to test anything"


def _initial(server, trial_id: int) -> dict[str, Any]:
    from server.store.tables import TrialRow

    with server.services.store.transaction() as session:
        return session.get(TrialRow, trial_id).initial_state
