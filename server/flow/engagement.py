"""Engagement as a validity rule: a main trial played without the participant taking part is ``low_engagement``
(docs/operations.md, "Engagement"). Judged when the trial ends, from its activity (``store.activity``) and the
study's ``validity`` section, and during the round on the activity so far (to warn the participant while they can
still act, ``server.game.taking_part``); pure.

A round is low-engagement when, in order (the first that applies is its reason, :data:`Rule`):

- ``no_actions``: the participant's actions (task choices plus interrupts) are fewer than
  ``validity.min_participant_actions`` (default 1: the robot played the round alone);
- ``idle``: its ``idle_pct`` (the share of tick periods in which the cook had nothing to do; on the paper's clock
  the waited time at the tick rate) is above ``validity.max_idle_pct``;
- ``task_steps``: the participant's share of the team's task steps (interactions that changed the world: picking
  up, putting down, chopping, washing, plating, delivering) is below ``validity.min_task_step_pct``: keys that
  change nothing (a held or tapped "stay") or tasks that never get anywhere left the work to the robot (judged once
  the team made at least :data:`MIN_TEAM_STEPS`: a share of a round too short to work in says nothing);
- ``refused_tasks``: more than ``validity.max_refused_task_pct`` of the participant's task choices in their main
  rounds so far (this one and the earlier ones, pooled) were refused — they could not work: what they needed was not
  there, or taken, or busy — once at least :data:`MIN_REFUSED` were: tasks chosen without looking at the kitchen.
  Pooled because one round says too little: a human-like simulated participant's single round reached 27.3 %,
  none of their pooled rounds more than 13.2 % (docs/protocol.md, "Taking part").

Practice trials and abandoned trials are not judged (an abandoned round is its own outcome).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Literal

from store.activity import Activity
from study_config.study.validity import Validity

LOW_ENGAGEMENT = "low_engagement"
Rule = Literal["no_actions", "idle", "task_steps", "refused_tasks"]
MIN_REFUSED = 5
"""Refused task choices a round must have before their share is judged: a few refusals say nothing."""
MIN_TEAM_STEPS = 10
"""Task steps the team must have made in a round before the participant's share of them is judged (the pilots'
rounds of the paper study had 28 to 147, the tapped-key script's 28)."""


@dataclass(frozen=True, slots=True)
class Problem:
    """Why a round is low-engagement: the rule, the measured value and the study's limit."""

    rule: Rule
    value: float
    limit: float

    def text(self) -> str:
        """The stored reason (``trials.engagement_reason``), e.g. ``low_engagement: the cook was idle 99.6 % of the
        round, more than 95 %``."""
        if self.rule == "no_actions":
            return f"{LOW_ENGAGEMENT}: {self.value:g} participant action(s), fewer than {self.limit:g}"
        if self.rule == "idle":
            return f"{LOW_ENGAGEMENT}: the cook was idle {self.value:.1f} % of the round, more than {self.limit:g} %"
        if self.rule == "task_steps":
            return (f"{LOW_ENGAGEMENT}: the participant made {self.value:.1f} % of the team's task steps, fewer than "
                    f"{self.limit:g} %")
        return (f"{LOW_ENGAGEMENT}: {self.value:.1f} % of the participant's task choices so far were refused, more "
                f"than {self.limit:g} %")

    def __str__(self) -> str:
        return self.text()

    def to_dict(self) -> dict[str, Any]:
        return {"reason": self.text(), "rule": self.rule, "value": round(self.value, 2), "limit": self.limit}


def engagement_problem(activity: Activity, validity: Validity, earlier: tuple[int, int] = (0, 0)) -> Problem | None:
    """Why a finished main trial with ``activity`` is low-engagement, or ``None`` when the participant took part;
    ``earlier``: the task choices and refused steps of the participant's earlier main rounds."""
    if activity.actions < validity.min_participant_actions:
        return Problem("no_actions", activity.actions, validity.min_participant_actions)
    idle = activity.idle_pct
    if idle is not None and idle > validity.max_idle_pct:
        return Problem("idle", idle, validity.max_idle_pct)
    share = activity.task_step_share
    team = activity.task_steps + activity.robot_task_steps
    if share is not None and team >= MIN_TEAM_STEPS and share < validity.min_task_step_pct:
        return Problem("task_steps", share, validity.min_task_step_pct)
    choices, refused = activity.selections + earlier[0], activity.refused_steps + earlier[1]
    refused_pct = 100.0 * refused / max(choices, 1)
    if refused >= MIN_REFUSED and refused_pct > validity.max_refused_task_pct:
        return Problem("refused_tasks", refused_pct, validity.max_refused_task_pct)
    return None
