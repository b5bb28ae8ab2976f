"""How many stored event rows a participant's messages may cause: a token bucket per live trial.

Every client message that stores a row (``select_subtask``, ``interrupt``, ``focus``, ``blur``, ``idle``)
takes one token; the bucket holds ``BURST`` tokens and refills at ``RATE_PER_S``. A message that finds the
bucket empty is refused (``error: rate_limited``, nothing changes, no row) and counted; the counts are stored
coalesced as one ``events_dropped`` row (``{"dropped": n, "by_kind": {...}}``) at most once a second while
the flood lasts, and when the trial ends or the participant disconnects. A person pressing keys as fast as
they can stays far below the rate (docs/protocol.md, "Errors"); a script flooding the socket stores at most
``RATE_PER_S`` + 1 rows a second instead of thousands. The bucket belongs to the trial, not the socket, so
reconnecting does not refill it. Simulated pilot participants (``steakhouse pilot``, admin-made) are not
limited: at pace ``fast`` they play many times faster than real time. The clock is injected (tests drive it).
"""

from __future__ import annotations

import time
from collections import Counter
from collections.abc import Callable
from typing import Any

RATE_PER_S = 20.0
"""Stored client events a second, sustained."""
BURST = 60
"""Stored client events at once after a quiet spell."""
SUMMARY_EVERY_S = 1.0
"""While messages are dropped, at most one ``events_dropped`` row this often."""


class EventBudget:
    def __init__(self, rate: float = RATE_PER_S, burst: int = BURST,
                 clock: Callable[[], float] = time.monotonic) -> None:
        self.rate, self.burst, self.clock = rate, burst, clock
        self.tokens = float(burst)
        self.at = clock()
        self.dropped: Counter[str] = Counter()
        self.total_dropped = 0
        self._summary_at: float | None = None

    def take(self, kind: str) -> bool:
        """Spend a token for one ``kind`` event; ``False`` (and the drop counted) when none is left."""
        now = self.clock()
        self.tokens = min(self.burst, self.tokens + (now - self.at) * self.rate)
        self.at = now
        if self.tokens >= 1:
            self.tokens -= 1
            return True
        self.dropped[kind] += 1
        self.total_dropped += 1
        return False

    def summary(self, force: bool = False) -> dict[str, Any] | None:
        """The ``events_dropped`` payload to store now (and the counts restart), or ``None``: nothing was dropped,
        or the last summary is less than ``SUMMARY_EVERY_S`` old (unless ``force``)."""
        if not self.dropped:
            return None
        now = self.clock()
        if not force and self._summary_at is not None and now - self._summary_at < SUMMARY_EVERY_S:
            return None
        self._summary_at = now
        payload = {"dropped": self.dropped.total(), "by_kind": dict(sorted(self.dropped.items()))}
        self.dropped.clear()
        return payload
