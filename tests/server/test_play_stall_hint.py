"""Over a real websocket: a participant who does nothing while the team gets nothing done is given a stall hint
(``stall_hint``) after ``timing.stall_hint_seconds``, stored as a ``stall_hint`` event and counted for the
dashboard; the hint names neither the robot's planner nor the condition."""

from __future__ import annotations

import asyncio

from steakhouse_testing import Player, eventually

from planner.registry import PLANNER_NAMES
from store import trials


def test_a_stalled_team_gets_a_hint_that_is_logged(live_server, study_file):
    # 30 Hz and 0.2 s: six ticks without progress.
    server = live_server([study_file(timing={"tick_rate_hz": 30, "stall_hint_seconds": 0.2})])

    async def scenario():
        player = Player(server.url)
        await player.ready()
        sock = await player.socket()
        hello = await sock.recv()
        hint = await sock.until(lambda m: m["type"] == "stall_hint")
        await sock.close()
        await player.close()
        return hello, hint

    hello, hint = asyncio.run(scenario())
    assert hint["code"] in ("standing_at_station", "onion_needs_chopping", "plate_needs_washing", "holding",
                            "look_around")
    assert not any(word in hint["text"].lower() for word in (*PLANNER_NAMES, "fov", "baseline", "condition"))
    trial_id = hello["trial"]["id"]

    def logged():
        with server.services.store.transaction() as session:
            return [e.payload for e in trials.events(session, trial_id) if e.kind == "stall_hint"]

    found = eventually(logged, lambda rows: len(rows) >= 1)
    assert found[0] == {"code": hint["code"], "text": hint["text"]}
    game = server.services.registry.games.get(trial_id)
    assert game is None or game.hints.stall_hints >= 1
