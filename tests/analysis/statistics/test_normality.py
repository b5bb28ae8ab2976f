"""Shapiro–Wilk on the ANOVA residuals (analysis.statistics.normality)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import stats
from steakhouse_published import REACTTIME

from analysis.statistics.normality import residual_normality, residuals


def test_residuals_remove_participant_and_cell_means() -> None:
    e = residuals(REACTTIME)
    assert e.mean(axis=0) == pytest.approx(np.zeros(6), abs=1e-9)
    assert e.mean(axis=1) == pytest.approx(np.zeros(10), abs=1e-9)
    result = residual_normality(REACTTIME)
    ref = stats.shapiro(e.ravel())
    assert (result.w, result.p) == pytest.approx((ref.statistic, ref.pvalue)) and result.n_residuals == 60


def test_additive_data_have_no_residuals_to_test() -> None:
    additive = np.add.outer(np.arange(5.0), np.array([1.0, 3.0, 4.0]))
    assert residual_normality(additive).note == "not testable: the residuals are all zero"
