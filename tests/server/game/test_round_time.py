"""The round's wall clock: connected time toward the limit, one nudge per idle stretch."""

from __future__ import annotations

import asyncio

from server.game.round_time import RoundTime


class Hand:
    def __init__(self) -> None:
        self.t = 100.0

    def now(self) -> float:
        return self.t

    async def wait(self, event: asyncio.Event, seconds: float | None) -> None:
        return None

    async def sleep(self, seconds: float) -> None:
        return None


def test_the_limit_counts_connected_time_only():
    clock = Hand()
    times = RoundTime(clock, limit_s=60.0, nudge_s=10.0)
    times.connected()
    clock.t += 40
    times.disconnected()
    clock.t += 500                      # away: the world is paused, the grace window applies instead
    assert times.elapsed() == 40 and not times.over_limit()
    times.connected()
    clock.t += 19
    assert times.take_countdown() == 1, "a round of a minute is counted down from its start"
    assert not times.over_limit() and times.until_next() == 1
    clock.t += 1
    assert times.over_limit()


def test_a_nudge_every_nudge_interval_of_an_idle_stretch_counted_from_the_stretch_or_a_reconnection():
    clock = Hand()
    times = RoundTime(clock, limit_s=None, nudge_s=10.0)
    times.connected()
    times.idle()
    clock.t += 9
    assert not times.take_nudge() and times.until_next() == 1
    clock.t += 1
    assert times.take_nudge() == 1 and not times.take_nudge()
    assert times.until_next() == 10, "the next reminder"
    clock.t += 10
    assert times.take_nudge() == 2
    times.acted()
    assert times.until_next() is None
    times.idle()
    clock.t += 10
    times.disconnected()
    assert not times.take_nudge(), "no nudge to nobody"
    times.connected()
    assert not times.take_nudge()
    clock.t += 10
    assert times.take_nudge() == 1


def test_the_last_minute_of_the_limit_is_counted_down_once_per_connection():
    clock = Hand()
    times = RoundTime(clock, limit_s=240.0, nudge_s=10.0)
    times.connected()
    assert times.left() == 240 and times.until_next() == 180, "the countdown is due at 60 s left"
    clock.t += 179
    assert times.take_countdown() is None
    clock.t += 1
    assert times.take_countdown() == 60 and times.take_countdown() is None
    assert times.until_next() == 60, "then the limit"
    clock.t += 30
    times.disconnected()
    times.connected()
    assert times.take_countdown() == 30, "a reconnected page is told again"
    assert RoundTime(clock, limit_s=None, nudge_s=10.0).take_countdown() is None, "the fixed clock has none"
