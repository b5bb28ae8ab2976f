"""What the report and the plots need to know about a measure: its label with unit, natural bounds, and whether it
is a rating (ordinal: rank tests beside the ANOVA) or discrete (jittered points).

Units come from the data dictionary (:data:`analysis.exports.dictionary.UNITS`). Natural bounds: 0–100 for percentages,
0 and up for counts, 0–4 for ``kb_gap_mean`` (four components), 0 to the horizon for ``ticks``, the item's scale for
a rating item or scale, 0–1 for flags. An unknown column (``analyze --csv``) has no unit and no bounds. A measure is
discrete when its values are whole numbers with few distinct values (ratings, small counts).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import pandas as pd

from analysis.exports.dictionary import FLAG, INT, MEASURES, UNITS
from planner.summary import GAP_COMPONENTS, KB_DIFF_MAX

MAX_DIVISOR = 24
"""Resolutions looked for: 1/k for k = 1..MAX_DIVISOR (a rating item: 1; the mean of k items: 1/k)."""
DISCRETE_VALUES = 15
"""A whole-number measure with at most this many distinct values is on a discrete scale (its points are jittered)."""


@dataclass(frozen=True, slots=True)
class MeasureInfo:
    name: str
    unit: str = ""
    lower: float = -math.inf
    upper: float = math.inf
    rating: bool = False
    discrete: bool = False
    resolution: float | None = None
    """The step of a rating measure's values (1 for an item, 1/k for a scale of k items), found in the data;
    ``None`` when its values are on no such grid (rank tests then round to 9 decimals)."""

    @property
    def label(self) -> str:
        """``ticks (world steps)``."""
        return f"{self.name} ({self.unit})" if self.unit else self.name

    def clip(self, low: float, high: float) -> tuple[float, float, bool]:
        """``(low, high)`` cut at the natural bounds, and whether anything was cut."""
        clipped = (max(low, self.lower), min(high, self.upper))
        return clipped[0], clipped[1], clipped != (low, high)


def measure_info(name: str, values: pd.Series, horizon: int | None = None,
                 ratings: Mapping[str, tuple[float, float]] | None = None) -> MeasureInfo:
    """The info of ``name``; ``ratings`` maps rating columns to their scale's (min, max) (``-inf, inf`` when
    unknown)."""
    finite = values.dropna().astype(float)
    discrete = bool(len(finite)) and bool(np.all(np.mod(finite, 1) == 0)) and finite.nunique() <= DISCRETE_VALUES
    if ratings is not None and name in ratings:
        low, high = ratings[name]
        return MeasureInfo(name, "rating", low, high, rating=True, discrete=discrete, resolution=resolution(finite))
    unit = UNITS.get(name, "")
    column = MEASURES.get(name)
    lower, upper = -math.inf, math.inf
    if unit == "%":
        lower, upper = 0.0, 100.0
    elif name == "kb_gap_mean":
        lower, upper = 0.0, float(len(GAP_COMPONENTS))
    elif name in ("kb_diff_avg", "kb_diff_mean"):
        lower, upper = 0.0, KB_DIFF_MAX
    elif name == "ticks":
        lower, upper = 0.0, float(horizon) if horizon else math.inf
    elif column is not None and column.type == FLAG:
        lower, upper = 0.0, 1.0
    elif (column is not None and column.type == INT) or unit == "ms":
        lower = 0.0
    return MeasureInfo(name, unit, lower, upper, discrete=discrete)


def resolution(values: pd.Series) -> float | None:
    """The coarsest step 1/k (k ≤ :data:`MAX_DIVISOR`) of which every value is a multiple (to 1e-6), or ``None``."""
    x = values.dropna().to_numpy(dtype=float)
    for k in range(1, MAX_DIVISOR + 1):
        if np.all(np.abs(x * k - np.round(x * k)) < 1e-6):
            return 1.0 / k
    return None
