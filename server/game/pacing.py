"""The clock of one live round (``server.game.live`` describes it): when the next step is due, the wall-clock
limit and idle nudge (``server.game.round_time``), and how late the steps started."""

from __future__ import annotations

from collections import deque

from server.game.clock import Clock
from server.game.round_time import RoundTime
from study_config.study.sections import Timing

LATENESS_KEPT = 5000
"""Steps whose lateness is kept for the live view's percentiles."""


class Pacing:
    def __init__(self, timing: Timing, horizon: int, clock: Clock, fast: bool, spent_s: float = 0.0) -> None:
        self.mode, self.rate, self.period = timing.mode, timing.tick_rate_hz, 1.0 / timing.tick_rate_hz
        self.fast = fast
        """A ``fast`` pilot trial: a step as soon as the simulated participant answered and the robot decided."""
        self.clock = clock
        """The wall clock of the round limit and the idle nudge (tests inject one they move by hand)."""
        self.times = RoundTime(clock, timing.round_limit_seconds(horizon), timing.idle_nudge_seconds, spent_s)
        self.lateness: deque[float] = deque(maxlen=LATENESS_KEPT)
        """Milliseconds each recent step started after its scheduled start."""

    def scheduled(self, now: float, last_start: float | None, next_at: float | None) -> float:
        """When the next step is due (``time.monotonic()``), given the start of the last step and, under
        ``fixed_rate``, the time the last step planned for the next (``None`` after a pause)."""
        if self.mode == "wait_for_participant":
            return now if last_start is None else max(last_start + self.period, now)
        return next_at if next_at is not None else now + self.period
