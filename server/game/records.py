"""The row stored for each tick (see ``store.tables.TickRow`` for the columns' meaning)."""

from __future__ import annotations

from typing import Any

from server.game.engine import TickOutcome
from server.robots import RobotChoice
from store.types import utcnow


def tick_row(trial_id: int, outcome: TickOutcome, choice: RobotChoice, lateness_ms: float,
             controller: dict[str, Any], round_seconds: float, epoch: int = 0) -> dict[str, Any]:
    """Joint action, the subtask the participant's action came from, modelled KB and world summaries, the
    KB-gap components and their sum, robot in the participant's FOV, lateness and decision time, the robot's
    decision record (or why it failed), the full world, KB and controller state (replay and resume read them), the
    step's world events (who loaded, chopped, washed, plated, delivered, or bumped into the other), what the
    participant's cook did in the step (``controller.step``: ``server.game.steps``), the seconds the round has run
    while the participant was connected (its limit's clock), and the lease epoch it was stepped under
    (``store.lease``: the store keeps it only while the epoch is the round's)."""
    return {
        "trial_id": trial_id, "tick": outcome.tick, "recorded_at": utcnow(),
        "human_action": outcome.human_action.value, "robot_action": outcome.robot_action.value,
        "action_source": outcome.source, "subtask": outcome.subtask.value if outcome.subtask else None,
        "kb_summary": outcome.kb_summary, "world_summary": outcome.world_summary, "kb_gap": outcome.gap,
        "kb_gap_total": sum(outcome.gap.values()), "robot_in_fov": outcome.robot_in_fov,
        "lateness_ms": round(lateness_ms, 3),
        "decision_ms": None if choice.decision_ms is None else round(choice.decision_ms, 3),
        "robot_missed": choice.missed, "robot_info": choice.info,
        "robot_error": choice.error[:300] if choice.failed and choice.error is not None else None,
        "world_state": outcome.world.to_dict(),
        "kb_state": outcome.kb.to_dict(), "controller": {**controller, "step": outcome.step},
        "world_events": [event.to_dict() for event in outcome.events], "round_seconds": round(round_seconds, 3),
        "epoch": epoch,
    }
