"""The paper's clock over a real websocket, its wall clock moved by hand: a task whose next step would do nothing
is refused with its reason and the world does not step (no tick is stored, the robot does not move) however long
the participant then waits; a key is one step; a task that walks steps as it walks."""

from __future__ import annotations

import asyncio

import pytest
from steakhouse_test_robots import simulated_partner
from steakhouse_testing import ENGAGEMENT_RULES, ManualClock, Player, eventually

from store import trials

pytestmark = pytest.mark.store_agnostic

PAPER = {"mode": "wait_for_participant", "tick_rate_hz": 30, "idle_nudge_seconds": 5, "max_round_seconds": 600}


def test_a_refused_step_moves_nothing_and_says_why_while_keys_and_walks_step(live_server, study_file):
    clock = ManualClock()
    server = live_server([study_file(timing=PAPER)], robot_factory=simulated_partner, clock=clock)

    async def scenario():
        player = Player(server.url)
        await player.ready()
        sock = await player.socket()
        hello = await sock.recv()
        first = await sock.until(lambda m: m["type"] == "state")
        await sock.send("select_subtask", subtask="pickup_clean_plate")  # no clean plate known: nothing to do
        refused = await sock.until(lambda m: m["type"] == "blocked")
        unchanged = await sock.until(lambda m: m["type"] == "state")
        clock.advance(30.0)  # the participant waits half a minute: nudges, no step
        await sock.until(lambda m: m["type"] == "nudge")
        await sock.send("heartbeat", client_time=1)
        await sock.until(lambda m: m["type"] == "pong")
        waited = [m for m in sock.received if m["type"] == "state"]
        await sock.send("interrupt", action="stay")
        stayed = await sock.until(lambda m: m["type"] == "state")
        await sock.send("select_subtask", subtask="pickup_meat")
        meat = await sock.until(lambda m: m["type"] == "state" and m["you"]["held"] == "meat", timeout=30)
        await sock.close()
        await player.close()
        return hello, first, refused, unchanged, waited, stayed, meat

    hello, first, refused, unchanged, waited, stayed, meat = asyncio.run(scenario())
    assert hello["mode"] == "wait_for_participant" and first["tick"] == 0
    assert refused == {**refused, "subtask": "pickup_clean_plate", "reason": "no_clean_plate", "ended": True}
    assert (unchanged["tick"], unchanged["subtask"]) == (0, None), "the task is gone, the world where it was"
    assert [s["tick"] for s in waited] == [0, 0], "30 s of waiting stepped nothing"
    assert stayed["tick"] == 1, "one key, one step"
    assert meat["tick"] > 1

    trial_id = hello["trial"]["id"]

    def stored():
        with server.services.store.transaction() as session:
            return trials.ticks(session, trial_id)

    rows = eventually(stored, lambda r: len(r) >= meat["tick"])
    steps = [r.controller["step"] for r in rows]
    assert steps[0] == "key" and set(steps[1:meat["tick"]]) <= {"walk", "work", "wait"}
    assert steps[meat["tick"] - 1] == "work"


def test_a_waiting_participant_is_reminded_warned_counted_down_and_told_the_true_reason(live_server, study_file):
    clock = ManualClock()
    timing = {**PAPER, "idle_nudge_seconds": 10, "max_round_seconds": 120}
    study = study_file(timing=timing, recruiting={"screen_out_code": "OUT-1"}, validity=ENGAGEMENT_RULES)
    server = live_server([study], clock=clock)

    async def scenario():
        player = Player(server.url)
        await player.ready()
        sock = await player.socket()
        await sock.until(lambda m: m["type"] == "state")
        await sock.send("interrupt", action="stay")  # one key: an action, no task step
        await sock.until(lambda m: m["type"] == "state" and m["tick"] == 1)
        clock.advance(10.0)
        first = await sock.until(lambda m: m["type"] == "nudge")
        clock.advance(10.0)
        second = await sock.until(lambda m: m["type"] == "nudge")
        warned = await sock.until(lambda m: m["type"] == "warning")
        clock.advance(40.0)  # 60 s left
        countdown = await sock.until(lambda m: m["type"] == "countdown")
        last_warning = await sock.until(lambda m: m["type"] == "warning")
        clock.advance(60.0)
        end = await sock.until(lambda m: m["type"] == "trial_end")
        await sock.close()
        session = await player.session()
        await player.close()
        return first, second, warned, countdown, last_warning, end, session, sock.received

    first, second, warned, countdown, last_warning, end, session, received = asyncio.run(scenario())
    assert (first["repeat"], second["repeat"]) == (1, 2), "the nudge repeats"
    assert warned["rule"] == "idle" and warned["seconds_left"] == 100
    assert countdown["seconds_left"] == 60 and last_warning["seconds_left"] == 60
    assert not any(m["type"] == "warning" for m in received[:received.index(second)]), "not at the first nudge"
    assert (end["reason"], end["next"]) == ("time_limit", "screened_out")
    completion = session["completion"]
    assert completion["reason"] == "low_engagement"
    assert completion["detail"]["rule"] == "idle" and completion["detail"]["round"] == 1
    assert completion["detail"]["value"] > 99 and completion["detail"]["limit"] == 95
