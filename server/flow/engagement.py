"""Engagement as a validity rule: a main trial played without the participant taking part is ``low_engagement``
(docs/operations.md, "Engagement"). Judged when the trial ends, from its activity (``store.activity``)
and the study's ``validity`` section; pure.

A finished main trial is low-engagement when

- the participant's actions (task choices plus interrupts) are fewer than ``validity.min_participant_actions``
  (default 1: the robot played the round alone), or
- its ``idle_pct`` (the share of tick periods in which the cook had nothing to do) is above
  ``validity.max_idle_pct``.

Practice trials and abandoned trials are not judged (an abandoned round is its own outcome).
"""

from __future__ import annotations

from store.activity import Activity
from study_config.study.validity import Validity

LOW_ENGAGEMENT = "low_engagement"


def engagement_problem(activity: Activity, validity: Validity) -> str | None:
    """Why a finished main trial with ``activity`` is low-engagement, or ``None`` when the participant took part."""
    if activity.actions < validity.min_participant_actions:
        return (f"{LOW_ENGAGEMENT}: {activity.actions} participant action(s), fewer than "
                f"{validity.min_participant_actions}")
    idle = activity.idle_pct
    if idle is not None and idle > validity.max_idle_pct:
        return f"{LOW_ENGAGEMENT}: the cook was idle {idle:.1f} % of the round, more than {validity.max_idle_pct:g} %"
    return None
