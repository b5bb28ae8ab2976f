"""The independent-groups t of the mixed design's follow-ups (``analysis.followups.mixed_followups.student_t``): scipy's
Student t, also when a group's values are all equal (which scipy warns about, and which failed a played study)."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy import stats

from analysis.followups.mixed_followups import student_t


def scipy_student(x: np.ndarray, y: np.ndarray) -> tuple[float, int, float, float, float]:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        result = stats.ttest_ind(x, y)
        ci = result.confidence_interval(0.95)
    return float(result.statistic), len(x) + len(y) - 2, float(result.pvalue), float(ci.low), float(ci.high)


@pytest.mark.parametrize("seed", range(5))
def test_it_is_scipys_student_t(seed: int) -> None:
    rng = np.random.default_rng(seed)
    x, y = rng.normal(3, 2, size=4 + seed), rng.normal(2, 1, size=3 + 2 * seed)
    assert student_t(x, y) == pytest.approx(scipy_student(x, y), rel=1e-10)


def test_a_group_whose_values_are_all_equal_is_tested_without_a_warning() -> None:
    x, y = np.array([74.0, 74.0, 74.0]), np.array([70.0, 75.0, 71.0, 73.0])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ours = student_t(x, y)
    assert ours == pytest.approx(scipy_student(x, y), rel=1e-10) and ours[2] < 1


def test_without_variance_or_participants_it_is_not_testable() -> None:
    t, df, p, low, high = student_t(np.array([5.0, 5.0]), np.array([3.0, 3.0, 3.0]))
    assert df == 3 and all(math.isnan(v) for v in (t, p, low, high))
    assert student_t(np.array([1.0]), np.array([2.0]))[1] == 0
