"""Malformed and illegal client messages get a typed error, change nothing, and the game goes on."""

from __future__ import annotations

import asyncio
import json
import random

import pytest
from steakhouse_testing import Player, ProcessServer, play_to_end
from websockets.exceptions import ConnectionClosed

from store.tables import EventRow

pytestmark = pytest.mark.store_agnostic

BAD = [
    ("not json at all", "bad_json", None),
    ('{"v": 1, "seq": 10, "type": "select_subtask", "subtask": "pickup_meat"', "bad_json", None),
    ("[1, 2, 3]", "invalid_message", None),
    ("[" * 3000 + "]" * 3000, "too_large", None),
    ("[" * 1500 + "]" * 1500, "bad_json", None),
    ('{"v": 1, "seq": 11, "type": "teleport", "to": [1, 1]}', "unknown_type", 11),
    ('{"v": 2, "seq": 12, "type": "heartbeat", "client_time": 1}', "unsupported_version", 12),
    ('{"seq": 13, "type": "heartbeat", "client_time": 1}', "unsupported_version", 13),
    ('{"v": 1, "seq": "14", "type": "interrupt", "action": "up"}', "invalid_message", None),
    ('{"v": 1, "seq": 15, "type": "interrupt", "action": 3}', "invalid_message", 15),
    ('{"v": 1, "seq": 16, "type": "interrupt", "action": "fly"}', "invalid_message", 16),
    ('{"v": 1, "seq": 17, "type": "select_subtask", "subtask": "pickup_everything"}', "invalid_message", 17),
    ('{"v": 1, "seq": 18, "type": "select_subtask", "subtask": "pickup_onion", "also": 1}', "invalid_message", 18),
    ('{"v": 1, "seq": 19, "type": "idle", "idle_ms": "5"}', "invalid_message", 19),
    ('{"v": 1, "seq": 20, "type": "heartbeat"}', "invalid_message", 20),
    (json.dumps({"v": 1, "seq": 21, "type": "idle", "idle_ms": 1, "pad": "x" * 100_000}), "too_large", None),
    ('{"v": 1, "seq": 22, "type": "\\ud800"}', "unknown_type", 22),
    ('{"v": 1, "seq": 23, "type": "select_subtask", "subtask": "\\udfff"}', "invalid_message", 23),
    ('{"v": 1, "seq": 24, "type": "idle", "idle_ms": 1, "\\u0000": "\\ud800"}', "invalid_message", 24),
    ('{"v": 1, "seq": 1, "type": "interrupt", "action": "up"}', "bad_seq", 1),
    ('{"v": 1, "seq": 2, "type": "interrupt", "action": "up"}', "bad_seq", 2),
    (b"\x00\x01binary", "bad_frame", None),
]


async def errors_for(sock, frames):
    replies = []
    for frame, _, _ in frames:
        await sock.send_raw(frame)
        replies.append(await sock.until(lambda m: m["type"] in ("error", "ack", "pong")))
    return replies


def test_each_malformed_message_gets_a_typed_error_and_changes_nothing(live_server, study_file):
    server = live_server([study_file(world={"orders": 1, "horizon": 400, "kb_delay": 1})])

    async def scenario():
        player = Player(server.url)
        await player.ready()
        sock = await player.socket()
        await sock.recv()
        await sock.recv()
        sock.seq = 1
        await sock.send_raw('{"v": 1, "seq": 2, "type": "select_subtask", "subtask": "pickup_onion"}')
        ack = await sock.until(lambda m: m["type"] == "ack")
        replies = await errors_for(sock, BAD)
        before = await sock.until(lambda m: m["type"] == "state")
        sock.seq = 100
        probe = await sock.send("interrupt", action="stay")
        probe_ack = await sock.until(lambda m: m["type"] == "ack")
        later = await sock.until(lambda m: m["type"] == "state" and m["tick"] > before["tick"] + 3)
        end = await play_to_end(sock)
        await sock.close()
        await player.close()
        return ack, replies, before, probe, probe_ack, later, end, sock.received

    ack, replies, before, probe, probe_ack, later, end, received = asyncio.run(scenario())
    assert ack["ack"] == 2 and ack["subtask"] == "pickup_onion"
    for (frame, code, ref), reply in zip(BAD, replies, strict=True):
        assert reply["type"] == "error", f"{frame[:40]!r} was not rejected"
        assert (reply["code"], reply["ref"]) == (code, ref), f"{frame[:40]!r}: {reply}"
    # On a loaded machine the avatar may already have done what it was asked (it holds the onion and the
    # subtask ended by itself); any other subtask would mean a rejected message changed it.
    done_as_asked = before["subtask"] is None and before["you"]["held"] == "onion"
    assert before["subtask"] == "pickup_onion" or done_as_asked, "no rejected message may change the subtask"
    assert probe_ack["ack"] == probe and probe_ack["queued"] == 1, "no rejected interrupt may be queued"
    assert later["ack"] == probe
    assert end["status"] == "finished"
    with server.services.store.transaction() as session:
        kinds = [e.kind for e in session.query(EventRow).filter_by(trial_id=end_trial_id(received))]
    assert kinds.count("select_subtask") >= 1 and kinds.count("interrupt") == 1
    assert kinds.count("error") == len(BAD)


def end_trial_id(received) -> int:
    trial_id: int = next(m for m in received if m["type"] == "hello")["trial"]["id"]
    return trial_id


def test_a_frame_above_the_socket_limit_drops_only_the_connection(live_server, study_file):
    server = live_server([study_file()], ws_max_frame_bytes=64 * 1024)

    async def scenario():
        player = Player(server.url)
        await player.ready()
        sock = await player.socket()
        hello = await sock.recv()
        await sock.send_raw("x" * (2 << 20))
        with pytest.raises(ConnectionClosed):
            while True:
                await sock.recv(timeout=5)
        again = await player.socket()
        hello2 = await again.recv()
        end = await play_to_end(again)
        await again.close()
        await player.close()
        return hello, hello2, end

    hello, hello2, end = asyncio.run(scenario())
    assert hello2["trial"]["id"] == hello["trial"]["id"] and end["status"] == "finished"


def test_random_frames_never_stop_the_game(live_server, study_file):
    server = live_server([study_file()])
    rng = random.Random(3)
    pieces = ['{', '}', '"v"', ':', '1', ',', '"seq"', '"type"', '"interrupt"', '"action"', '"up"', '[', ']',
              'null', 'true', '"select_subtask"', '"subtask"', '"pickup_meat"', '9999999999999999999999', '-1',
              '"\\u0000"', '1e400', '"heartbeat"', '"client_time"']

    async def scenario():
        player = Player(server.url)
        await player.ready()
        sock = await player.socket()
        await sock.recv()
        replies = 0
        for _ in range(300):
            await sock.send_raw("".join(rng.choice(pieces) for _ in range(rng.randint(0, 14))))
            replies += 1
        answered = 0
        while answered < replies:
            message = await sock.recv()
            answered += message["type"] in ("error", "ack", "pong")
        end = await play_to_end(sock)
        await sock.close()
        await player.close()
        return end

    assert asyncio.run(scenario())["status"] == "finished"


def test_a_text_frame_that_is_not_utf8_closes_1007_without_a_traceback(db_url, study_file, tmp_path):
    """``steakhouse serve``'s own log: one warning line, no traceback; the participant reconnects and plays on."""
    log = tmp_path / "server.log"
    server = ProcessServer(study=study_file(), database_url=db_url, workers=0, log=log,
                           env={"STEAKHOUSE_LOG_LEVEL": "info"}).start()
    try:
        async def scenario():
            player = Player(server.url)
            await player.ready()
            sock = await player.socket()
            hello = await sock.recv()
            await sock.ws.send(b'{"v": 1, "seq": 5, "type": "idle", "idle_ms": 1, "x": "\xff\xfe"}', text=True)
            with pytest.raises(ConnectionClosed):
                while True:
                    await sock.recv(timeout=5)
            again = await player.socket()
            hello2 = await again.recv()
            end = await play_to_end(again)
            await again.close()
            await player.close()
            return hello, sock.ws.close_code, hello2, end

        hello, code, hello2, end = asyncio.run(scenario())
    finally:
        server.stop()
    assert code == 1007
    assert hello2["trial"]["id"] == hello["trial"]["id"] and end["status"] == "finished"
    text = log.read_text()
    assert "websocket closed with 1007" in text and "Traceback" not in text, text[-2000:]
