"""What the participant is told beside the kitchen's state while a live round runs, each told and logged:

- why their subtask is not getting anywhere (``blocked``; logged as ``subtask_blocked`` once it ended:
  ``server.game.blocked``);
- a hint when the team has been stuck for ``timing.stall_hint_seconds`` (``stall_hint``: ``server.game.stall_hint``);
- in both clocks, a ``nudge`` every ``timing.idle_nudge_seconds`` of a stretch in which their cook has nothing to do
  (naming nothing of the condition), the ``countdown`` of the round's last minute (``server.game.round_time``), and
  from the second nudge on, or with the countdown (never before they could act), a ``warning`` when the round so
  far would not count (``server.game.taking_part``).
"""

from __future__ import annotations

from server.game import snapshot
from server.game.blocked import Blocked
from server.game.engine import TickOutcome, TrialEngine
from server.game.link import ParticipantLink
from server.game.records import EventLog
from server.game.round_time import RoundTime
from server.game.stall_hint import StallHints
from server.game.taking_part import TakingPart
from server.protocol.server import Countdown, EngagementWarning, Nudge, StallHint


class Hints:
    def __init__(self, stall_ticks: int, link: ParticipantLink, log: EventLog, times: RoundTime,
                 part: TakingPart) -> None:
        self.stalls = StallHints(stall_ticks)
        self.link, self.log, self.times, self.part = link, log, times, part

    @property
    def stall_hints(self) -> int:
        """Stall hints given so far."""
        return self.stalls.given

    def blocked(self, blocked: Blocked) -> None:
        """Tell the participant why their subtask is not getting anywhere; log it when the subtask ended."""
        if blocked.ended:
            place = {"place": blocked.reason.place} if blocked.reason.place else {}
            self.log("subtask_blocked", {"subtask": blocked.subtask.value if blocked.subtask else None,
                                         "reason": blocked.reason.code, "item": blocked.reason.item, **place})
        self.link.send(snapshot.blocked_message(blocked))

    def stepped(self, engine: TrialEngine, outcome: TickOutcome) -> None:
        """After each step: the subtask's blocked notice, if any, and the stall hint once the team is stuck."""
        if outcome.blocked is not None:
            self.blocked(outcome.blocked)
        hint = self.stalls.step(engine.layout, engine.rules, outcome.world, outcome.kb, outcome.events)
        if hint is not None:
            self.log("stall_hint", {"code": hint.code, "text": hint.text})
            self.link.send(StallHint(code=hint.code, text=hint.text))

    def nudge(self) -> None:
        """Send the idle stretch's nudges and the countdown as they fall due, with the warning when it is due."""
        times = self.times
        if self.link.connection is None:
            return
        repeat = times.take_nudge()
        if repeat:
            self.link.send(Nudge(repeat=repeat))
            self.log("nudge", {"repeat": repeat})
        left = times.take_countdown()
        if left is not None:
            self.link.send(Countdown(seconds_left=round(left, 1)))
            self.log("countdown", {"seconds_left": round(left, 1)})
        due = (repeat >= 2 or left is not None) and times.elapsed() >= times.nudge_s  # never before they could act
        problem = self.part.problem() if due else None
        if problem is not None:
            self.link.send(EngagementWarning(rule=problem.rule, seconds_left=times.left()))
            self.log("engagement_warning", {"rule": problem.rule, "value": round(problem.value, 2)})
