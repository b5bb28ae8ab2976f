"""Practice and main rounds are numbered separately ("Practice 2 of 2", "Round 1 of 2") in the session view
and in the websocket's ``hello``, next to the overall number among all trials."""

from __future__ import annotations

import asyncio

from steakhouse_testing import Player, play_every_trial


def test_practice_and_main_rounds_have_their_own_numbering(live_server, study_file):
    server = live_server([study_file(robots=["stay", "fov_aware"],
                                     practice=[{"kitchen": "none_3", "robot": "stay", "count": 2}],
                                     world={"orders": 1, "horizon": 3, "kb_delay": 1})])

    async def scenario():
        player = Player(server.url)
        await player.ready()
        played = await play_every_trial(player)
        await player.close()
        return [trial for trial, _ in played], [hello["trial"] for _, hello in played]

    sessions, hellos = asyncio.run(scenario())
    expected = [("practice", 1, 2, 1, 4), ("practice", 2, 2, 2, 4), ("main", 1, 2, 3, 4), ("main", 2, 2, 4, 4)]
    for shown in (sessions, hellos):
        assert [(t["kind"], t["kind_number"], t["kind_total"], t["number"], t["total"]) for t in shown] == expected
