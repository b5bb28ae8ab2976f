"""Wall-clock accounting of one live round: how long it has run while the participant was connected (the
``wait_for_participant`` limit, ``timing.max_round_seconds``), and how long the cook has stood with nothing
to do (the nudge after ``timing.idle_nudge_seconds``). Time comes from an injected :class:`~server.game.clock.Clock`.

- The limit counts connected time only: while nobody is connected the world is paused and the reconnect grace
  window applies instead. A round resumed from the store (after a restart, or by another process) goes on
  from the seconds stored with its last tick (``spent_s``; rounds stored before those were kept count from their
  resumption).
- An idle stretch starts when the cook has nothing to do (no task, no key waiting) and ends with the
  participant's next accepted choice or key; a nudge is due every ``idle_nudge_seconds`` of it (the first
  ``idle_nudge_seconds`` into it, counted again from a reconnection), so a participant who waits is reminded again.
- The countdown: when the last :data:`COUNTDOWN_SECONDS` of the wall-clock limit begin, once per connection (a
  reconnected page is told again), the participant is shown the seconds left.
"""

from __future__ import annotations

from server.game.clock import Clock

COUNTDOWN_SECONDS = 60.0
"""The last seconds of a round's wall-clock limit in which the participant sees them counted down."""


class RoundTime:
    def __init__(self, clock: Clock, limit_s: float | None, nudge_s: float, spent_s: float = 0.0) -> None:
        self.clock, self.limit_s, self.nudge_s = clock, limit_s, nudge_s
        self._spent = spent_s
        self._since: float | None = None
        self._idle_from: float | None = None
        self._nudges = 0
        """Nudges given in the current idle stretch."""
        self._counted_down = False

    def connected(self) -> None:
        now = self.clock.now()
        if self._since is None:
            self._since = now
        if self._idle_from is not None:
            self._idle_from, self._nudges = now, 0
        self._counted_down = False

    def disconnected(self) -> None:
        if self._since is not None:
            self._spent += self.clock.now() - self._since
            self._since = None

    def elapsed(self) -> float:
        """Seconds the round has run while connected."""
        return self._spent + (self.clock.now() - self._since if self._since is not None else 0.0)

    def over_limit(self) -> bool:
        return self.limit_s is not None and self.elapsed() >= self.limit_s

    def left(self) -> float | None:
        """Seconds left before the wall-clock limit (``None``: no limit, the fixed clock)."""
        return None if self.limit_s is None else max(self.limit_s - self.elapsed(), 0.0)

    def acted(self) -> None:
        """The participant chose a task or pressed a key: the idle stretch ends."""
        self._idle_from, self._nudges = None, 0

    def idle(self) -> None:
        """The cook has nothing to do (the stretch starts now unless it already runs)."""
        if self._idle_from is None:
            self._idle_from, self._nudges = self.clock.now(), 0

    def take_nudge(self) -> int:
        """The number of the idle stretch's nudge due now (1, 2, …: the whole intervals the stretch has lasted;
        each answered once, a late ask skips the missed ones), or 0."""
        if self._idle_from is None or self._since is None:
            return 0
        due = int((self.clock.now() - self._idle_from) // self.nudge_s)
        if due <= self._nudges:
            return 0
        self._nudges = due
        return due

    def take_countdown(self) -> float | None:
        """The seconds left when the countdown is due now (the last :data:`COUNTDOWN_SECONDS` of the limit have
        begun and this connection has not been told), else ``None``."""
        left = self.left()
        if left is None or self._counted_down or self._since is None or left > COUNTDOWN_SECONDS:
            return None
        self._counted_down = True
        return left

    def until_next(self) -> float | None:
        """Seconds until the next nudge, the countdown or the limit is due (``None``: none)."""
        now = self.clock.now()
        waits = []
        left = self.left()
        if left is not None:
            waits.append(left)
            if not self._counted_down:
                waits.append(left - COUNTDOWN_SECONDS)
        if self._idle_from is not None:
            waits.append(self._idle_from + self.nudge_s * (self._nudges + 1) - now)
        return max(min(waits), 0.0) if waits else None
