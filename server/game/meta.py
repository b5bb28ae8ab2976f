"""The fixed facts of one live trial (from its row and the participant's plan step)."""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any


@dataclass(frozen=True, slots=True)
class TrialMeta:
    trial_id: int
    attempt: int
    participant_id: int
    participant: str
    """The participant's public id."""
    study_id: str
    kind: str
    index: int
    number: int
    total: int
    kind_total: int
    """Trials of this kind (practice or main) in the participant's plan."""
    condition: str
    robot: str
    kitchen: str
    view: str
    """How the participant sees the kitchen (``study_config.study.views``); the one condition fact they may be told."""
    seed: int
    test_run: bool
    pilot_pace: str | None = None
    """``fast`` or ``realtime`` for a simulated pilot participant (from the store's pilot mark, never from a
    client message); ``None`` for a real participant."""
    epoch: int = 0
    """The round's lease epoch this server process runs it under (``store.lease``): its ticks and events carry it,
    and the store refuses them once another process has taken the round over."""

    def to_dict(self) -> dict[str, Any]:
        """For the admin (JSON): the seed as text, since JavaScript numbers keep only 53 bits."""
        return {**asdict(self), "seed": str(self.seed)}
