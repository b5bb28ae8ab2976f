"""Questionnaire scales (analysis.measures.scale_scores): reverse coding and scoring."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from analysis.measures.scale_scores import reversed_values, score_scales
from analysis.source.study_design import RatingItem, ScaleSpec

ITEMS = (RatingItem("q.a", 1, 7), RatingItem("q.b", 1, 7, reverse=True), RatingItem("q.c", 1, 7))
SCALE = ScaleSpec("q.fluency", "Fluency", ("q.a", "q.b", "q.c"))


def test_reverse_coding_is_max_plus_min_minus_value() -> None:
    values = pd.Series([1, 4, 7])
    assert reversed_values(values, ITEMS[1]).tolist() == [7, 4, 1]
    assert reversed_values(values, ITEMS[0]).tolist() == [1, 4, 7]


def test_scale_score_is_the_mean_after_reversal_and_missing_items_leave_no_score() -> None:
    cells = pd.DataFrame({"q.a": [7, 2, 5], "q.b": [1, 6, None], "q.c": [6, 3, 5]})
    scored = score_scales(cells, ITEMS, (SCALE,))
    assert scored["q.fluency"].tolist()[:2] == pytest.approx([(7 + 7 + 6) / 3, (2 + 2 + 3) / 3])
    assert np.isnan(scored["q.fluency"].iloc[2])
    assert scored["q.b"].tolist()[:2] == [1, 6]  # the item itself keeps the answer as given
