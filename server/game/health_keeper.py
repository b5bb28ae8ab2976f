"""The robot health of one live trial, kept current and in the store (``server.game.health`` judges it; docs/
operations.md, "Robot health").

Every decision is counted; the moment the trial becomes invalid it says so in the server log, in a
``trial_invalid`` event and on the trial row (written off the event loop). At the end the health is judged over
the decisions the trial made and stored once more.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
from collections.abc import Callable, Sequence
from typing import Any

from planner.events import Event
from planner.rules import Rules
from planner.state import WorldState
from server.game.health import RobotHealth
from server.game.meta import TrialMeta
from store import trials
from store.engine import Store
from study_config.study.validity import Validity

log = logging.getLogger("server.game.live")
"""The game's log: a trial turning invalid is reported where the rest of its story is."""


class HealthKeeper:
    def __init__(self, health: RobotHealth, store: Store, meta: TrialMeta,
                 event: Callable[[str, dict[str, Any]], None]) -> None:
        self.health, self.store, self.meta, self.event = health, store, meta, event
        self._writes: set[asyncio.Task[None]] = set()

    @classmethod
    def fresh(cls, validity: Validity, horizon: int, store: Store, meta: TrialMeta,
              event: Callable[[str, dict[str, Any]], None], health: RobotHealth | None = None) -> HealthKeeper:
        """The keeper of ``health`` (a resumed trial's, recounted from its ticks) or, if none, of a new trial's,
        judged by the study's ``validity`` thresholds."""
        return cls(health or RobotHealth(validity.max_missed_decisions_pct, horizon,
                                         max_flickers=validity.max_robot_flickers), store, meta, event)

    def record(self, missed: bool, failed: bool = False) -> None:
        """Count one decision (late: ``missed``; the robot's fault: ``failed``); the moment the trial becomes
        invalid, say so and store it."""
        self.take(self.health.record(missed, failed))

    def stepped(self, before: WorldState, events: Sequence[Event], rules: Rules) -> None:
        """Watch the step from ``before`` for a flicker of the robot (:meth:`RobotHealth.stepped`), as :meth:`record`
        counts a decision."""
        self.take(self.health.stepped(before, events, rules))

    def take(self, health: RobotHealth) -> None:
        """Take ``health``; the moment it makes the trial invalid, say so and store it."""
        if self.update(health, "is invalid"):
            task = asyncio.create_task(asyncio.to_thread(self.store_now, self.health))
            self._writes.add(task)
            task.add_done_callback(self._writes.discard)

    def update(self, health: RobotHealth, verb: str) -> bool:
        """Take ``health``; when it makes the trial invalid, log a warning and a ``trial_invalid`` event and
        answer ``True``."""
        became_invalid = health.invalid and not self.health.invalid
        self.health = health
        if became_invalid:
            log.warning("trial %d (participant %s) %s: %s", self.meta.trial_id, self.meta.participant, verb,
                        health.invalid_reason)
            self.event("trial_invalid", health.to_dict())
        return became_invalid

    def store_now(self, health: RobotHealth) -> None:
        """Write ``health``'s counts and reason on the trial row (blocking: call it in a thread)."""
        with self.store.transaction() as session:
            trials.record_health(session, self.meta.trial_id, decisions=health.decisions, missed=health.missed,
                                 invalid_reason=health.invalid_reason, failed=health.failed, epoch=self.meta.epoch)

    def finish(self) -> None:
        """The trial ends: judge the health over the decisions it made (:meth:`RobotHealth.final`); a trial that
        turns invalid only now says so (stored by :meth:`settle`)."""
        self.update(self.health.final(), "ended invalid")

    async def settle(self) -> None:
        """Wait for the writes under way, then store the health as it is now."""
        if self._writes:
            await asyncio.gather(*self._writes, return_exceptions=True)
        await asyncio.to_thread(self.store_now, self.health)

    async def keep(self) -> None:
        """The trial is suspended: store the counts if the store lets us (they are recounted from the ticks on
        resume anyway)."""
        with contextlib.suppress(Exception):
            await asyncio.to_thread(self.store_now, self.health)
