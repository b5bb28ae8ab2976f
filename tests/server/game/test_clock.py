"""The real wall clock of a live round (``server.game.clock``): it never goes back, and a bounded wait returns as
soon as its event is set, or at once when no time is left."""

from __future__ import annotations

import asyncio

from server.game.clock import MonotonicClock


def test_the_clock_never_goes_back() -> None:
    clock = MonotonicClock()
    readings = [clock.now() for _ in range(1000)]
    assert readings == sorted(readings)


def test_a_wait_ends_when_its_event_is_set_or_no_time_is_left() -> None:
    async def scenario() -> tuple[bool, bool, bool]:
        clock, event = MonotonicClock(), asyncio.Event()
        await clock.wait(event, 0.0)  # nothing left to wait: returns with the event unset
        unset = not event.is_set()
        waiting = asyncio.ensure_future(clock.wait(event, None))  # no limit: only the event ends it
        await asyncio.sleep(0)
        still_waiting = not waiting.done()
        event.set()
        await waiting
        await clock.wait(event, -1.0)  # a negative wait is no wait
        return unset, still_waiting, waiting.done()

    assert asyncio.run(scenario()) == (True, True, True)
