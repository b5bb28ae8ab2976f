"""A participant's messages cannot store thousands of event rows a second: past a burst, messages are refused
(``rate_limited``, nothing applied) and counted in coalesced ``events_dropped`` rows; a person's pace is never
limited, and the game goes on."""

from __future__ import annotations

import asyncio
import time
from typing import Any

import pytest
from steakhouse_testing import Player, eventually, play_to_end

from server.game.budget import BURST, RATE_PER_S, EventBudget
from store.tables import EventRow

pytestmark = pytest.mark.store_agnostic


class Clock:
    def __init__(self) -> None:
        self.now = 100.0

    def __call__(self) -> float:
        return self.now


def test_the_bucket_allows_a_burst_then_the_rate_and_counts_every_drop():
    clock = Clock()
    budget = EventBudget(rate=10, burst=5, clock=clock)
    assert [budget.take("interrupt") for _ in range(7)] == [True] * 5 + [False] * 2
    assert budget.summary() == {"dropped": 2, "by_kind": {"interrupt": 2}}
    assert budget.take("focus") is False and budget.summary() is None, "at most one summary a second"
    clock.now += 0.35
    assert [budget.take("select_subtask") for _ in range(4)] == [True, True, True, False]
    clock.now += 1.0
    assert budget.summary() == {"dropped": 2, "by_kind": {"focus": 1, "select_subtask": 1}}
    assert budget.summary(force=True) is None, "nothing new to report"
    assert budget.total_dropped == 4


def test_a_persons_pace_is_never_limited():
    clock = Clock()
    budget = EventBudget(clock=clock)
    for _ in range(600):  # a minute of eight key presses a second, the fastest a person keeps up
        clock.now += 1 / 8
        assert budget.take("interrupt")


def test_a_flood_of_messages_stores_a_bounded_number_of_rows_and_the_game_goes_on(live_server, study_file):
    server = live_server([study_file(world={"orders": 1, "horizon": 3000, "kb_delay": 1})])
    flood = 3000

    async def scenario():
        player = Player(server.url)
        await player.ready()
        sock = await player.socket()
        hello = await sock.recv()
        started = time.monotonic()
        for _ in range(flood):
            await sock.send("focus")
        replies: list[dict[str, Any]] = []
        while len(replies) < flood:
            message = await sock.recv()
            if message["type"] in ("ack", "error"):
                replies.append(message)
        elapsed = time.monotonic() - started
        # The game goes on: a move after the flood is answered (applied, or refused if the bucket is still empty,
        # which a loaded machine makes more likely; either way its answer is counted below).
        await sock.send("interrupt", action="stay")
        while True:
            message = await sock.recv()
            if message["type"] in ("ack", "error"):
                last = message
                break
        await sock.close()
        again = await player.socket()
        await again.recv()
        await again.close()
        await player.close()
        return hello["trial"]["id"], replies, elapsed, last

    trial_id, replies, elapsed, last = asyncio.run(scenario())
    refused = [r for r in replies if r["type"] == "error"]
    assert {r["code"] for r in refused} == {"rate_limited"}
    accepted = flood - len(refused)
    assert BURST <= accepted <= BURST + RATE_PER_S * elapsed + 1, (accepted, elapsed)

    def rows():
        with server.services.store.transaction() as session:
            return [(e.kind, e.payload) for e in session.query(EventRow).filter_by(trial_id=trial_id)]

    def both_connections_closed(found: list[tuple[str, Any]]) -> bool:
        # Both connections' rows (the reconnection's connect stored or counted as dropped, and its disconnect) reach
        # the store in a later batch than the first connection's.
        connects = sum(kind == "connect" for kind, _ in found) + sum(
            payload["by_kind"].get("connect", 0) for kind, payload in found if kind == "events_dropped")
        return connects == 2 and sum(kind == "disconnect" for kind, _ in found) == 2

    stored = eventually(rows, both_connections_closed)
    focus = [payload for kind, payload in stored if kind == "focus"]
    dropped = [payload for kind, payload in stored if kind == "events_dropped"]
    assert len(focus) == accepted, "every applied message has its row, no refused one has"
    assert last["type"] == "ack" or last["code"] == "rate_limited"
    late_drop = int(last["type"] == "error")
    # The reconnection after the flood takes from the same budget (a reconnection flood is one too): when the
    # bucket is still empty its connect row is counted instead of stored.
    reconnects = sum(d["by_kind"].get("connect", 0) for d in dropped)
    assert sum(d["dropped"] for d in dropped) == len(refused) + late_drop + reconnects, "every drop is counted"
    assert sum(d["by_kind"].get("focus", 0) for d in dropped) == len(refused)
    assert all(set(d["by_kind"]) <= {"focus", "interrupt", "connect"} for d in dropped)
    assert reconnects + sum(1 for kind, _ in stored if kind == "connect") == 2
    # At most one row per flush of the flood, plus the reconnection's own when it was counted (after the close).
    assert len(dropped) <= elapsed / 1.0 + 2 + reconnects, "the drops are coalesced"
    assert not any(kind == "error" for kind, _ in stored), "refusals for the rate do not store rows"
    print(f"\n{flood} focus messages in {elapsed:.2f} s: {accepted} stored, {len(refused)} refused, "
          f"{len(dropped)} events_dropped rows ({(accepted + len(dropped)) / elapsed:.0f} rows/s)")


def test_the_game_plays_to_the_end_under_the_limit(live_server, study_file):
    server = live_server([study_file()])

    async def scenario():
        player = Player(server.url)
        await player.ready()
        sock = await player.socket()
        end = await play_to_end(sock)
        await sock.close()
        await player.close()
        return end, sock.received

    end, received = asyncio.run(scenario())
    assert end["status"] == "finished"
    assert not any(m["type"] == "error" and m["code"] == "rate_limited" for m in received)
