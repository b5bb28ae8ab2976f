"""Names of the robot planners a study or a simulation may ask for (docs/domain.md §5, "The robots"): every one is a
level a study file's ``robots:`` may name."""

from __future__ import annotations

PLANNER_NAMES: tuple[str, ...] = ("fov_aware", "fov_aware_showing", "baseline", "no_rollout", "stay")
