"""The consent a participant reads counts the rounds they will play: with the field of view between participants,
their group's rounds (here 1 practice + 3), never every group's (1 + 6)."""

from __future__ import annotations

import asyncio

from steakhouse_testing import Player


def test_a_between_participants_consent_counts_the_participants_own_rounds(live_server, study_file):
    consent = ("You will play {rounds} short rounds ({practice_rounds} practice), {main_rounds} that count; "
               "about {minutes} minutes.")
    server = live_server([study_file(robots=["stay", "fov_aware", "baseline"], fov_angles=[90, 150],
                                     between=["fov_angle"], world={"orders": 1, "horizon": 300},
                                     practice=[{"kitchen": "practice", "robot": "stay"}], consent=consent)])

    async def scenario():
        player = Player(server.url)
        await player.join()
        session = await player.session()
        await player.close()
        return session

    session = asyncio.run(scenario())
    assert session["state"] == "consent"
    assert session["consent"].startswith("You will play 4 short rounds (1 practice), 3 that count; about ")
    assert session["trials_total"] == 4
