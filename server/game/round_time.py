"""Wall-clock accounting of one live round: how long it has run while the participant was connected (the
``wait_for_participant`` limit, ``timing.max_round_seconds``), and how long the cook has stood with nothing
to do (the nudge after ``timing.idle_nudge_seconds``). Time comes from an injected :class:`~server.game.clock.Clock`.

- The limit counts connected time only: while nobody is connected the world is paused and the reconnect grace
  window applies instead. A round resumed from the store (after a restart, or by another process) goes on
  from the seconds stored with its last tick (``spent_s``; rounds stored before those were kept count from their
  resumption).
- An idle stretch starts when the cook has nothing to do (no task, no key waiting) and ends with the
  participant's next accepted choice or key; one nudge is due per stretch, ``idle_nudge_seconds`` into it
  (counted again from a reconnection).
"""

from __future__ import annotations

from server.game.clock import Clock


class RoundTime:
    def __init__(self, clock: Clock, limit_s: float | None, nudge_s: float, spent_s: float = 0.0) -> None:
        self.clock, self.limit_s, self.nudge_s = clock, limit_s, nudge_s
        self._spent = spent_s
        self._since: float | None = None
        self._idle_from: float | None = None
        self._nudged = False

    def connected(self) -> None:
        now = self.clock.now()
        if self._since is None:
            self._since = now
        if self._idle_from is not None:
            self._idle_from, self._nudged = now, False

    def disconnected(self) -> None:
        if self._since is not None:
            self._spent += self.clock.now() - self._since
            self._since = None

    def elapsed(self) -> float:
        """Seconds the round has run while connected."""
        return self._spent + (self.clock.now() - self._since if self._since is not None else 0.0)

    def over_limit(self) -> bool:
        return self.limit_s is not None and self.elapsed() >= self.limit_s

    def acted(self) -> None:
        """The participant chose a task or pressed a key: the idle stretch ends."""
        self._idle_from, self._nudged = None, False

    def idle(self) -> None:
        """The cook has nothing to do (the stretch starts now unless it already runs)."""
        if self._idle_from is None:
            self._idle_from, self._nudged = self.clock.now(), False

    def take_nudge(self) -> bool:
        """Whether the nudge of the current idle stretch is due now (answered ``True`` once per stretch)."""
        if self._idle_from is None or self._nudged or self._since is None:
            return False
        if self.clock.now() - self._idle_from < self.nudge_s:
            return False
        self._nudged = True
        return True

    def until_next(self) -> float | None:
        """Seconds until the nudge or the limit is due (``None``: neither)."""
        now = self.clock.now()
        waits = []
        if self.limit_s is not None:
            waits.append(self.limit_s - self.elapsed())
        if self._idle_from is not None and not self._nudged:
            waits.append(self._idle_from + self.nudge_s - now)
        return max(min(waits), 0.0) if waits else None
