"""When a trial counts as data: the study's ``validity`` section (docs/operations.md, "Robot health")."""

from __future__ import annotations

from pydantic import Field

from server.study.base import StudyModel

DEFAULT_MAX_MISSED_DECISIONS_PCT = 5.0
"""A trial whose robot missed more than this share of its decision deadlines is invalid (issue 13, part 3)."""


class Validity(StudyModel):
    """Rules that mark a trial invalid as it happens; invalid trials are left out of the analysis by default."""

    max_missed_decisions_pct: float = Field(default=DEFAULT_MAX_MISSED_DECISIONS_PCT, ge=0, le=100)
    """The robot stood still for a missed decision; past this share of the trial's decisions (in %) the trial
    did not test the robot the condition names, and is marked invalid with the share as the reason."""
