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
from steakhouse_masking import check_masked
from steakhouse_test_robots import simulated_partner
from steakhouse_testing import Player

pytestmark = pytest.mark.store_agnostic

MOVES = ("up", "down", "left", "right")


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
        if message["type"] != "state" or message["hud"]["ticks_left"] == 0 or message["hud"]["orders_left"] == 0:
            continue  # the round's last state: the server closes the socket after its trial_end
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
    states = [m for m in received if m["type"] == "state"]
    assert len(states) >= 60
    robot_seen, robot_hidden = check_masked(server, hello["trial"]["id"], [hello, *received])
    assert robot_seen > 0 and robot_hidden > 0, "the trial must show and hide the robot to test anything"
