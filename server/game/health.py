"""Robot health of one trial: the share of robot decisions that missed their deadline or failed, and when that
makes the trial invalid (docs/operations.md, "Robot health").

A missed decision (late) or a failed one (the robot raised, answered an illegal decision or hung, or its worker
was lost: ``planner.robot_guard``) makes the robot stand still for that tick (``server.robots.choice``), so a
trial with many of them did not test the robot its condition names. The study's
``validity.max_missed_decisions_pct`` (P) judges both together (``lost`` = missed + failed):

- **as it happens**: the trial is invalid as soon as ``lost > P % × horizon``. A trial makes at most
  ``horizon`` decisions, so its final share is then certain to exceed P whatever happens next;
- **at the end**: the trial is invalid when ``lost > P % × decisions`` (a trial that ended early, all orders
  delivered, is judged on the decisions it made).

A robot that undoes its own last touch of a counter while nothing else has changed (puts a plate down and picks it
up again, :mod:`planner.flicker`) flickers; the planners never choose to, so each such cycle is counted from outside
(:meth:`RobotHealth.stepped`) and more than the study's ``validity.max_robot_flickers`` (default 0) makes the trial
invalid as it happens, like the missed decisions.

Once invalid, a trial stays invalid. The state is an immutable value; :meth:`RobotHealth.record` returns the
next one.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Any

from planner.events import Event
from planner.flicker import FlickerWatch
from planner.rules import Rules
from planner.state import WorldState


@dataclass(frozen=True, slots=True)
class RobotHealth:
    threshold_pct: float
    """The study's ``validity.max_missed_decisions_pct``."""
    horizon: int
    """The most decisions a trial can make (one per world step)."""
    decisions: int = 0
    missed: int = 0
    invalid_reason: str | None = None
    failed: int = 0
    """Decisions the robot failed (counted apart from the late ones: ``missed``)."""
    max_flickers: int = 0
    """The study's ``validity.max_robot_flickers``."""
    touches: FlickerWatch = field(default_factory=FlickerWatch)
    """The robot's last touch and its undone touches so far (counted in this process: a resumed trial starts at 0)."""

    @property
    def lost(self) -> int:
        """Decisions the robot did not make in time: late or failed."""
        return self.missed + self.failed

    @property
    def flickers(self) -> int:
        return self.touches.flickers

    @property
    def flickered(self) -> bool:
        return self.flickers > self.max_flickers

    @property
    def missed_pct(self) -> float:
        return 100.0 * self.lost / self.decisions if self.decisions else 0.0

    @property
    def invalid(self) -> bool:
        return self.invalid_reason is not None

    def record(self, missed: bool, failed: bool = False) -> RobotHealth:
        """The health after one more decision (``missed``: it came after its deadline; ``failed``: the robot
        failed it)."""
        after = replace(self, decisions=self.decisions + 1, missed=self.missed + int(missed),
                        failed=self.failed + int(failed and not missed))
        if not after.invalid and 100.0 * after.lost > after.threshold_pct * after.horizon:
            return replace(after, invalid_reason=after.reason())
        return after

    def stepped(self, before: WorldState, events: Sequence[Event], rules: Rules) -> RobotHealth:
        """The health after the world's step from ``before`` (``events``: the step's): a flicker past the study's
        limit makes the trial invalid."""
        now = replace(self, touches=self.touches.observe(before, events, rules))
        if not now.invalid and now.flickered:
            return replace(now, invalid_reason=(f"the robot undid its own last interaction {now.flickers} times "
                                                f"with nothing else changed (> {now.max_flickers})"))
        return now

    def final(self) -> RobotHealth:
        """The health judged over the decisions the trial made (at its end); a flicker's reason stays."""
        if (100.0 * self.lost > self.threshold_pct * self.decisions
                or (self.invalid and not self.flickered)):
            return replace(self, invalid_reason=self.reason())
        return self

    def reason(self) -> str:
        if not self.failed:
            return (f"robot decisions missed their deadline: {self.missed} of {self.decisions} "
                    f"({self.missed_pct:.1f} % > {self.threshold_pct:g} %)")
        return (f"robot decisions missed their deadline or failed: {self.missed} missed and {self.failed} failed "
                f"of {self.decisions} ({self.missed_pct:.1f} % > {self.threshold_pct:g} %)")

    def to_dict(self) -> dict[str, Any]:
        return {"decisions": self.decisions, "missed": self.missed, "failed": self.failed,
                "missed_pct": round(self.missed_pct, 2), "threshold_pct": self.threshold_pct,
                "flickers": self.flickers, "max_flickers": self.max_flickers,
                "invalid": self.invalid, "invalid_reason": self.invalid_reason}
