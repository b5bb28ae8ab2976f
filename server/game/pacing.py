"""The clock of one live round: when the world steps, how long the round has run, and how late its steps started.

- ``fixed_rate``: a step every ``1 / tick_rate_hz`` seconds; ``wait_for_participant`` (the paper's clock): a
  step only for an action of the participant's (a key's one action, or a step of their task that moves, turns
  or works: a task whose next step would do nothing ends with its reason instead, ``server.game.steps``),
  never faster than the tick rate.
- **The world is paused while no participant is connected** (the researcher's choice: a dropped
  connection must not cost the participant ticks); the next step comes one period after they return.
- Tick lateness = actual start of a step − its scheduled start (logged per tick). A late step does not
  cause a burst of catch-up steps.
- A pilot participant's trial at pace ``fast`` (``steakhouse pilot``; the pace is the store's pilot mark, so no
  real participant can get it) steps as soon as the simulated participant has answered the last ``state``
  with any message (it sends a heartbeat when it has nothing to do) and the robot has decided; it waits at most
  one period for that answer (the robot's side: ``server.game.decisions``).
- ``wait_for_participant`` rounds have a wall-clock limit (``timing.max_round_seconds``, counted while the
  participant is connected, and stored with each tick so a round resumed from the store goes on counting):
  past it the round ends with reason ``time_limit``. Each stretch the world waits
  for the participant is logged as a ``wait`` event (its seconds count toward the trial's ``idle_pct``); the
  nudges and the countdown due meanwhile are the hints' (``server.game.hints``).

Two clocks are injected: ``clock``, the round's wall clock (its limit, the idle stretches, the waits for the
participant: ``server.game.round_time``), which tests move by hand; and ``ticker``, the steps' schedule (real time
by default, so a round whose limit a test holds still keeps stepping).
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable

from server.game.blocked import Blocked
from server.game.clock import Clock, MonotonicClock
from server.game.engine import TrialEngine
from server.game.link import ParticipantLink
from server.game.records import EventLog
from server.game.round_time import RoundTime
from study_config.study.sections import Timing

LATENESS_KEPT = 5000
"""Steps whose lateness is kept for the live view's percentiles."""


class Pacing:
    def __init__(self, timing: Timing, horizon: int, clock: Clock, *, fast: bool, link: ParticipantLink,
                 log: EventLog, spent_s: float = 0.0, ticker: Clock | None = None) -> None:
        self.mode, self.rate, self.period = timing.mode, timing.tick_rate_hz, 1.0 / timing.tick_rate_hz
        self.fast = fast
        """A ``fast`` pilot trial: a step as soon as the simulated participant answered and the robot decided."""
        self.clock = clock
        """The wall clock of the round limit, the idle stretches and the waits for the participant."""
        self.ticker: Clock = ticker or MonotonicClock()
        """The clock the steps are scheduled on."""
        self.link, self.log = link, log
        self.times = RoundTime(clock, timing.round_limit_seconds(horizon), timing.idle_nudge_seconds, spent_s)
        self.lateness: deque[float] = deque(maxlen=LATENESS_KEPT)
        """Milliseconds each recent step started after its scheduled start."""
        self.waiting_since: float | None = None
        """When the current wait for the participant began (:attr:`clock`), while the world waits: the round's
        lease renewals store it, so a crash does not lose it from the idle share (``store.lease``)."""
        self.timed_out = False
        """The round reached its wall-clock limit: it ends with reason ``time_limit``."""
        self._next_at: float | None = None
        self._last_start: float | None = None
        self._started = self._scheduled = 0.0

    def connected(self, idle: bool) -> None:
        """The participant (re)connected; ``idle``: their cook has nothing to do."""
        self.times.connected()
        if idle:
            self.times.idle()

    def scheduled(self, now: float) -> float:
        """When the next step is due (:attr:`ticker`), given the start of the last step and, under ``fixed_rate``,
        the time the last step planned for the next (none after a pause)."""
        if self.mode == "wait_for_participant":
            return now if self._last_start is None else max(self._last_start + self.period, now)
        return self._next_at if self._next_at is not None else now + self.period

    async def due(self, engine: TrialEngine, refuse: Callable[[Blocked], None],
                  nudge: Callable[[], None]) -> float | None:
        """Wait until the world may step; the step's lateness (milliseconds), or ``None``: look again (the
        participant left or came back, the world waited for them, the step was refused) or the round's time is up
        (:attr:`timed_out`). ``refuse`` is told why the paper's clock refused the participant's task; ``nudge`` is
        asked after each wait for the participant."""
        link = self.link
        if not link.connected.is_set():
            await link.connected.wait()
            self._next_at = None
            return None
        if self.times.over_limit():
            self.timed_out = True
            return None
        now = self.ticker.now()
        if self.fast:
            await self._await_answer()
            scheduled = now = self.ticker.now()
        elif self.mode == "wait_for_participant" and not engine.controller.has_action():
            await self._wait_for_participant(nudge)
            return None
        else:
            scheduled = self.scheduled(now)
        if scheduled > now:
            await self.ticker.sleep(scheduled - now)
        if not link.connected.is_set() or not self._may_step(engine, refuse):
            return None
        self._scheduled, self._started = scheduled, self.ticker.now()
        lateness = max(self._started - scheduled, 0.0) * 1000
        self.lateness.append(lateness)
        return lateness

    def stepped(self, idle: bool) -> None:
        """The step :meth:`due` allowed is done (``idle``: the cook now has nothing to do); the next is due one period
        after it was, or now if that has passed."""
        if idle:
            self.times.idle()
        self._last_start = self._started
        self._next_at = max(self._scheduled + self.period, self.ticker.now())

    def _may_step(self, engine: TrialEngine, refuse: Callable[[Blocked], None]) -> bool:
        """The paper's clock steps only for the participant's actions (``server.game.steps``): a subtask whose next
        step would do nothing they chose ends, ``refuse`` is told why, and the world does not step; nor does it for a
        cook left with nothing to do meanwhile (a ``stop``). Asked right before each step, after any message that
        came meanwhile."""
        if self.mode != "wait_for_participant":
            return True
        refused = engine.refused_step()
        if refused is not None:
            refuse(refused)
            return False
        return self.fast or engine.controller.has_action()

    async def _wait_for_participant(self, nudge: Callable[[], None]) -> None:
        """The cook has nothing to do, so the world waits for the participant's next choice or key (or a
        disconnection), at most until the nudge or the round's limit is due; the stretch is logged as ``wait``."""
        times, clock = self.times, self.clock
        times.idle()
        self.link.wake.clear()
        began = self.waiting_since = clock.now()
        await clock.wait(self.link.wake, times.until_next())
        self.waiting_since = None
        waited = clock.now() - began
        if waited > 0:
            self.log("wait", {"seconds": round(waited, 3)})
        nudge()

    async def _await_answer(self) -> None:
        """A ``fast`` pilot trial: wait (at most a period) for the participant's answer to the last state."""
        answered = self.link.answered
        if not answered.is_set():
            await self.ticker.wait(answered, self.period)
        answered.clear()
