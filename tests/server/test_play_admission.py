"""Admission control over real websockets: with one slot, the second participant waits (told their place in
line, nothing about their round), then plays; one who waits too long is screened out with ``server_full``."""

from __future__ import annotations

import asyncio
from typing import Any

from steakhouse_testing import Player, eventually, play_to_end

from store.tables import EventRow

STUDY = {"world": {"orders": 1, "horizon": 60, "kb_delay": 1}}


def admission_events(server) -> list[dict[str, Any]]:
    with server.services.store.transaction() as session:
        return [e.payload for e in session.query(EventRow).filter_by(kind="admission_wait").order_by(EventRow.id)]


def test_with_one_slot_the_second_participant_waits_then_plays(live_server, study_file):
    server = live_server([study_file(**STUDY)], max_live_trials=1)
    registry = server.services.registry

    async def scenario():
        first, second = Player(server.url), Player(server.url)
        await first.ready()
        await second.ready()
        sock1 = await first.socket()
        hello1 = await sock1.recv()
        sock2 = await second.socket()
        waiting = await sock2.recv()
        # The first participant's round keeps going while the second waits.
        end1 = await play_to_end(sock1)
        hello2 = await sock2.until(lambda m: m["type"] != "waiting")
        end2 = await play_to_end(sock2)
        for thing in (sock1, sock2, first, second):
            await thing.close()
        return hello1, waiting, end1, hello2, end2, sock2.received

    hello1, waiting, end1, hello2, end2, received2 = asyncio.run(scenario())
    assert hello1["type"] == "hello"
    assert waiting == {"v": 1, "seq": 1, "type": "waiting", "position": 1, "eta_s": waiting["eta_s"]}
    assert waiting["eta_s"] > 0
    assert end1["status"] == "finished"
    assert hello2["type"] == "hello" and hello2["seq"] == len([m for m in received2 if m["type"] == "waiting"]) + 1
    assert end2["status"] == "finished"
    assert [m["seq"] for m in received2] == list(range(1, len(received2) + 1))
    events = eventually(lambda: admission_events(server), lambda e: len(e) == 1)
    assert events[0]["outcome"] == "admitted" and events[0]["first_position"] == 1 and events[0]["capacity"] == 1
    assert eventually(lambda: registry.lobby.admission.live, lambda n: n == 0) == 0


def test_a_participant_who_waits_too_long_is_screened_out(live_server, study_file):
    server = live_server([study_file(**STUDY, recruiting={"screen_out_code": "BUSY123"})], max_live_trials=1,
                         admission_max_wait_s=0.5)

    async def scenario():
        first, second = Player(server.url), Player(server.url)
        await first.ready()
        await second.ready()
        sock1 = await first.socket()
        await sock1.recv()
        sock2 = await second.socket()
        waiting = await sock2.recv()
        refusal = await sock2.until(lambda m: m["type"] != "waiting")
        session = await second.session()
        for thing in (sock1, sock2, first, second):
            await thing.close()
        return waiting, refusal, session

    waiting, refusal, session = asyncio.run(scenario())
    assert waiting["type"] == "waiting"
    assert refusal["type"] == "error" and refusal["code"] == "server_full"
    assert session["state"] == "screened_out"
    assert session["completion"]["reason"] == "server_full" and session["completion"]["code"] == "BUSY123"
    events = eventually(lambda: admission_events(server), lambda e: len(e) == 1)
    assert events[0]["outcome"] == "timeout"


def test_a_participant_who_leaves_the_line_frees_their_place(live_server, study_file):
    server = live_server([study_file(**STUDY)], max_live_trials=1)
    registry = server.services.registry

    async def scenario():
        first, second = Player(server.url), Player(server.url)
        await first.ready()
        await second.ready()
        sock1 = await first.socket()
        await sock1.recv()
        sock2 = await second.socket()
        await sock2.recv()
        await sock2.close()
        for thing in (sock1, first, second):
            await thing.close()

    asyncio.run(scenario())
    events = eventually(lambda: admission_events(server), lambda e: len(e) == 1)
    assert events[0]["outcome"] == "left"
    assert registry.lobby.admission.waiting == 0


def test_a_reloaded_tab_keeps_the_place_in_line(live_server, study_file):
    server = live_server([study_file(**STUDY)], max_live_trials=1)
    registry = server.services.registry

    async def scenario():
        first, second, third = Player(server.url), Player(server.url), Player(server.url)
        for player in (first, second, third):
            await player.ready()
        sock1 = await first.socket()
        await sock1.recv()
        old = await second.socket()
        await old.recv()
        behind = await third.socket()
        behind_first = await behind.recv()
        reloaded = await second.socket()  # the same participant, a new tab, before the old one closes
        again = await reloaded.recv()
        await old.close()
        await play_to_end(sock1)
        hello = await reloaded.until(lambda m: m["type"] != "waiting")
        await play_to_end(reloaded)
        third_hello = await behind.until(lambda m: m["type"] != "waiting")
        for thing in (sock1, reloaded, behind, first, second, third):
            await thing.close()
        return behind_first, again, hello, third_hello

    behind_first, again, hello, third_hello = asyncio.run(scenario())
    assert behind_first["position"] == 2
    assert again["type"] == "waiting" and again["position"] == 1
    assert hello["type"] == "hello" and third_hello["type"] == "hello"
    assert eventually(lambda: registry.lobby.admission.waiting, lambda n: n == 0) == 0
