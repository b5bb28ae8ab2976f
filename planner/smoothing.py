"""The running average of each robot subtask's rollout value (``PlannerConfig.value_smoothing``; docs/domain.md §5).

One seeded rollout per hypothesis is noisy, and a robot that flips between subtasks on noise can leave the person
stuck; averaging each subtask's value with its values at the previous ticks lowers the noise at no extra cost. The
average restarts when what it averages changes meaning: the robot's held object or the orders left.
"""

from __future__ import annotations

from planner.subtasks import Subtask


class ValueAverages:
    """Exponential averages of subtask values, weight ``alpha`` for the newest value (1: no averaging)."""

    def __init__(self, alpha: float) -> None:
        self.alpha = alpha
        self.averages: dict[Subtask, float] = {}
        self.key: tuple[str | None, int] | None = None

    def reset(self) -> None:
        self.averages, self.key = {}, None

    def restart_on(self, key: tuple[str | None, int]) -> None:
        """Start the averages anew when ``key`` (what the robot holds, the orders left) changed."""
        if key != self.key:
            self.averages, self.key = {}, key

    def fold(self, subtask: Subtask, value: float) -> float:
        """``value`` folded into ``subtask``'s running average; the new average."""
        before = self.averages.get(subtask)
        self.averages[subtask] = value if before is None else self.alpha * value + (1.0 - self.alpha) * before
        return self.averages[subtask]
