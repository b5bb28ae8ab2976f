"""The participant's part in each trial, as the server stored it when the trial ended (docs/operations.md,
"Engagement"): the ``trials.csv`` columns of their activity and the trial's status for analysis.

``trial_status``: ``running``, ``abandoned``, ``low_engagement`` (finished, but the participant did not take
part), ``robot_invalid`` (finished, the robot's decisions missed their deadlines too often) or ``finished``: the
rule the server judges a participant's rounds by, ``study_config.study.validity.round_status``.
"""

from __future__ import annotations

from typing import Any

from analysis.source.store_reader import StoredTrial
from study_config.study.validity import round_status


def trial_status(trial: StoredTrial) -> str:
    return round_status(trial.status, trial.engagement_reason, trial.invalid_reason)


def participation_values(trial: StoredTrial) -> dict[str, Any]:
    """The trial's ``trials.csv`` columns of :data:`analysis.exports.dictionary.PARTICIPATION_COLUMNS`."""
    return {"trial_status": trial_status(trial), "key_actions": trial.key_actions, "idle_pct": trial.idle_pct,
            "refused_steps": trial.refused_steps, "delivered_by_participant": trial.delivered_by_participant,
            "delivered_by_robot": trial.delivered_by_robot, "task_steps": trial.task_steps,
            "robot_task_steps": trial.robot_task_steps, "stand_ticks": trial.stand_ticks,
            "think_seconds": trial.think_seconds, "engagement_reason": trial.engagement_reason}
