"""A worker's reply to a decision request, as the game loop's :class:`~server.robots.choice.RobotChoice`."""

from __future__ import annotations

from typing import Any

from planner.geometry import Action
from server.robots.choice import RobotChoice


def choice_from_reply(status: str, payload: Any, elapsed_ms: float) -> RobotChoice:
    """``("ok", (action, info))`` → the action; ``"lost"`` (no planner, dead worker) or ``"error"`` (the
    planner raised; ``payload`` is the message) → the robot stays, with the reason."""
    if status == "ok":
        action, info = payload
        return RobotChoice(Action(action), decision_ms=elapsed_ms, info=info)
    return RobotChoice(Action.STAY, decision_ms=elapsed_ms, error="worker_lost" if status == "lost" else payload)
