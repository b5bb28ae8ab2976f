"""The person's perception defaults, one home each (docs/domain.md §3): the paper's 120° field of view and a
KB delay of 3 ticks. The kitchen's numbers (cook / chop / wash times, orders, horizon) have theirs in
:class:`planner.rules.Rules`. Study files, CLI options, the simulated human and the robot's model of the
person all read these; a study that changes them changes what the robot models (docs/domain.md §5)."""

from __future__ import annotations

FOV_ANGLE: float = 120.0
"""Degrees of the person's field of view."""
KB_DELAY: int = 3
"""Consecutive ticks something must stay in view before it enters the person's knowledge base."""
