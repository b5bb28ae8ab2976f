"""The wall clock of a live round, injected so that tests can move it by hand (``tests`` pass a manual clock).

:class:`Clock` is what :class:`server.game.round_time.RoundTime` and the game loop ask for the time, for a
bounded wait and for a sleep; :class:`MonotonicClock` is the real one (``time.monotonic``, an asyncio timeout and
``asyncio.sleep``, which the step schedule uses every tick: no event and no timeout task to make).
"""

from __future__ import annotations

import asyncio
import contextlib
import time
from typing import Protocol


class Clock(Protocol):
    def now(self) -> float:
        """Seconds on a clock that never goes back."""
        ...

    async def wait(self, event: asyncio.Event, seconds: float | None) -> None:
        """Return when ``event`` is set or ``seconds`` have passed on this clock (``None``: no limit)."""
        ...

    async def sleep(self, seconds: float) -> None:
        """Return once ``seconds`` have passed on this clock (the steps' schedule: nothing can cut it short)."""
        ...


class MonotonicClock:
    def now(self) -> float:
        return time.monotonic()

    async def wait(self, event: asyncio.Event, seconds: float | None) -> None:
        if seconds is None:
            await event.wait()
            return
        with contextlib.suppress(TimeoutError):
            await asyncio.wait_for(event.wait(), max(seconds, 0.0))

    async def sleep(self, seconds: float) -> None:
        await asyncio.sleep(max(seconds, 0.0))
