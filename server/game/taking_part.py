"""The round's taking part so far, so that a participant is told while they can still act that the round, ended
now, would not count (docs/protocol.md, "Taking part"; the judgement is ``server.flow.engagement``'s).

It counts what ``store.activity`` counts when the round ends — choices, interrupts and keys, refused steps, waited
seconds, ticks and idle ticks, each cook's task steps — from the same events and steps, as they happen in this
process. A round resumed from the store counts from its resumption here; the judgement at its end counts it whole.
Practice rounds are never judged, nor a round once its robot's health made it invalid (as at its end).
"""

from __future__ import annotations

from typing import Any

from server.flow.engagement import Problem, engagement_problem
from server.game.engine import TickOutcome
from server.game.steps import acted
from store.activity import KEY_ACTIONS, Activity
from study_config.study.validity import Validity


class TakingPart:
    def __init__(self, validity: Validity, tick_rate_hz: float, judged: bool) -> None:
        self.validity, self.rate, self.judged = validity, tick_rate_hz, judged
        self.counts = {"select_subtask": 0, "interrupt": 0, "key": 0, "subtask_blocked": 0}
        self.waited = 0.0
        self.ticks = self.idle_ticks = self.stand_ticks = 0
        self.steps = {"human": 0, "robot": 0}

    def note(self, kind: str, payload: dict[str, Any]) -> None:
        """One stored event of the round (the others are ignored). Once the robot's health made the round invalid
        (``trial_invalid``) it is no longer judged: what a broken robot did is not the participant's to answer for."""
        if kind == "trial_invalid":
            self.judged = False
        elif kind in self.counts:
            self.counts[kind] += 1
            self.counts["key"] += kind == "interrupt" and payload.get("action") in KEY_ACTIONS
        elif kind == "wait":
            self.waited += float(payload.get("seconds", 0.0))

    def stepped(self, outcome: TickOutcome) -> None:
        """One world step of the round."""
        self.ticks += 1
        self.idle_ticks += outcome.source == "idle"
        self.stand_ticks += outcome.step in ("stand", "idle")
        for agent in self.steps:
            self.steps[agent] += sum(1 for e in outcome.events if acted((e,), agent))

    def activity(self) -> Activity:
        c = self.counts
        return Activity(selections=c["select_subtask"], interrupts=c["interrupt"], key_actions=c["key"],
                        ticks=self.ticks, idle_ticks=self.idle_ticks, waited_seconds=self.waited,
                        refused_steps=c["subtask_blocked"], delivered_by_participant=0, delivered_by_robot=0,
                        tick_rate_hz=self.rate, task_steps=self.steps["human"], robot_task_steps=self.steps["robot"],
                        stand_ticks=self.stand_ticks)

    def problem(self) -> Problem | None:
        """Why the round, ended now, would be low-engagement (``None``: it would count, or it is practice)."""
        return engagement_problem(self.activity(), self.validity) if self.judged else None
