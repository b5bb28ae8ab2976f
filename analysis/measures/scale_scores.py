"""Questionnaire scales: reverse coding and scale scores (their internal consistency is
:mod:`analysis.statistics.reliability`).

* A reverse-coded rating item (``reverse: true``) on a min..max scale is reversed as max + min − value before it
  enters a scale (a 7 on a 1–7 item becomes a 1). Items analysed on their own keep the value as answered.
* A scale's score is the mean of its items after reversal, per participant and condition; a cell missing any of
  the scale's items has no score (no prorating), and the complete-case rule then says so.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pandas as pd

from analysis.source.study_design import RatingItem, ScaleSpec


def reversed_values(values: pd.Series, item: RatingItem) -> pd.Series:
    """The item's values as they enter a scale: max + min − value when reverse-coded."""
    return item.maximum + item.minimum - values if item.reverse else values


def score_scales(cells: pd.DataFrame, items: Sequence[RatingItem], scales: Sequence[ScaleSpec]) -> pd.DataFrame:
    """``cells`` with one column per scale (the mean of its items after reversal; NaN if one is missing)."""
    by_column = {item.column: item for item in items}
    out = cells.copy()
    for scale in scales:
        present = [c for c in scale.items if c in out.columns]
        if not present:
            out[scale.column] = np.nan
            continue
        scored = pd.concat([reversed_values(out[c].astype(float), by_column[c]) for c in present], axis=1)
        out[scale.column] = scored.mean(axis=1, skipna=False)
    return out


def response_scores(values: Mapping[str, Any], items: Sequence[RatingItem], scales: Sequence[ScaleSpec]
                    ) -> dict[str, float | None]:
    """The scores of one response (``values``: item column → answer, absent or ``None`` when not answered), scored
    as :func:`score_scales` scores a table; ``None`` for a scale missing an item."""
    answers = pd.DataFrame([{c: values.get(c) for scale in scales for c in scale.items}], dtype=float)
    scored = score_scales(answers, items, scales)
    return {s.column: None if pd.isna(scored[s.column].iloc[0]) else float(scored[s.column].iloc[0])
            for s in scales}
