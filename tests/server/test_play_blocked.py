"""Over a real websocket: ``hello`` gives what the hands need for each subtask and the part of the grid worth
drawing; a choice that does not fit what the cook holds is refused with a typed ``blocked`` message; a subtask
that cannot progress ends itself with its reason, stored as a ``subtask_blocked`` event; the game goes on."""

from __future__ import annotations

import asyncio

import pytest
from steakhouse_testing import Player, eventually

from server.game.needs import NEEDS
from server.game.view import drawn_bounds
from store import trials
from study_config import load_layout

pytestmark = pytest.mark.store_agnostic


def test_a_blocked_choice_is_explained_and_logged_and_the_game_goes_on(live_server, study_file):
    # 30 Hz and 0.2 s: a subtask without progress ends after 6 ticks.
    server = live_server([study_file(timing={"tick_rate_hz": 30, "blocked_subtask_seconds": 0.2})])

    async def scenario():
        player = Player(server.url)
        await player.ready()
        sock = await player.socket()
        hello = await sock.recv()
        await sock.send("select_subtask", subtask="deliver_dish")      # empty hands: refused at once
        refused = await sock.until(lambda m: m["type"] == "blocked")
        ack = await sock.until(lambda m: m["type"] == "ack")
        await sock.send("select_subtask", subtask="pickup_clean_plate")  # no clean plate known: ends itself
        notice = await sock.until(lambda m: m["type"] == "blocked")
        ended = await sock.until(lambda m: m["type"] == "blocked")
        after = await sock.until(lambda m: m["type"] == "state")
        await sock.send("select_subtask", subtask="pickup_meat")
        meat = await sock.until(lambda m: m["type"] == "state" and m["you"]["held"] == "meat", timeout=20)
        await sock.close()
        await player.close()
        return hello, refused, ack, notice, ended, after, meat

    hello, refused, ack, notice, ended, after, meat = asyncio.run(scenario())
    assert hello["needs"] == {s.value: need for s, need in NEEDS.items()}
    layout = load_layout("practice")
    assert tuple(hello["bounds"].values()) == drawn_bounds(layout) == (0, 0, 10, 7)
    assert hello["trial"]["scored"] is True
    assert refused == {**refused, "subtask": "deliver_dish", "reason": "needs_item", "item": "dish", "ended": True}
    assert ack["subtask"] is None, "the refused choice did not become the task"
    assert notice == {**notice, "subtask": "pickup_clean_plate", "reason": "no_clean_plate", "ended": False}
    assert ended == {**ended, "subtask": "pickup_clean_plate", "reason": "no_clean_plate", "ended": True}
    assert after["subtask"] is None and meat["you"]["held"] == "meat"

    trial_id = hello["trial"]["id"]

    def logged():
        with server.services.store.transaction() as session:
            return [(e.kind, e.payload) for e in trials.events(session, trial_id) if e.kind == "subtask_blocked"]

    found = eventually(logged, lambda rows: len(rows) == 2)
    assert found == [("subtask_blocked", {"subtask": "deliver_dish", "reason": "needs_item", "item": "dish"}),
                     ("subtask_blocked", {"subtask": "pickup_clean_plate", "reason": "no_clean_plate", "item": None})]
