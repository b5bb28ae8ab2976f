"""Simulated questionnaire answers (labelled simulated everywhere: the pilot mark travels with the participant).

The model, per rating item: ``rating_mean − rating_gap_slope · g + ε``, ε ~ Normal(0, ``rating_sd``), where g is
the mean KB gap per frame the simulated participant measured in the trial the questionnaire follows (stations
and robot cargo it found different from what it believed; ``Perception.gap_mean``), for items on a 1..7
scale; on another scale the mean and slope are scaled to its range. Reversed items (``reverse: true``) are
mirrored (min + max − value), so a larger gap lowers the scale score. The value is rounded and clipped to the
item's scale. Choice items take a uniformly random option; text items say they are simulated (within the item's
length limits); optional text items are left empty.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from pilot.config import ParticipantConfig

SIMULATED_TEXT = "simulated pilot participant"


def answer(questionnaire: Mapping[str, Any], gap_mean: float, config: ParticipantConfig, reversed_items: set[str],
           rng: np.random.Generator) -> dict[str, Any]:
    """Answers to every item of ``questionnaire`` (the session view's ``questionnaire`` object)."""
    out: dict[str, Any] = {}
    for item in questionnaire["items"]:
        kind = item.get("type", "rating")
        if kind == "rating":
            low, high = int(item["scale"]["min"]), int(item["scale"]["max"])
            span = (high - low) / 6.0
            centre = low + (config.rating_mean - 1.0) * span - config.rating_gap_slope * span * gap_mean
            value = centre + rng.normal(0.0, config.rating_sd * span) if config.rating_sd > 0 else centre
            value = int(np.clip(round(value), low, high))
            out[item["id"]] = low + high - value if item["id"] in reversed_items else value
        elif kind == "choice":
            out[item["id"]] = int(rng.integers(len(item["options"])))
        elif item.get("required", True):
            text = SIMULATED_TEXT
            minimum = int(item.get("min_length") or 0)
            out[item["id"]] = (text * (minimum // len(text) + 1))[: max(minimum, len(text))]
    return out
