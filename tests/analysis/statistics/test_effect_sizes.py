"""Confidence intervals of effect sizes (analysis.statistics.effect_sizes) against published values and their
definitions."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats
from steakhouse_published import JASP_PROPORTIONS

from analysis.statistics.effect_sizes import dz_ci, partial_eta2_ci, percentile_interval


def test_dz_interval_matches_jasp() -> None:
    # JASP's one-sample t test of JASP_PROPORTIONS against 0.5 (jaspTTests test-ttestonesample.R):
    # t = -0.385804772181173,
    # Cohen's d = -0.0909350568744795 with 95% CI [-0.552576696667502, 0.373348871605267]. A one-sample d of
    # differences is the paired d_z.
    diff = JASP_PROPORTIONS - 0.5
    t = stats.ttest_1samp(diff, 0).statistic
    assert t == pytest.approx(-0.385804772181173, rel=1e-10)
    assert dz_ci(t, len(diff)) == pytest.approx((-0.552576696667502, 0.373348871605267), rel=1e-8)


def test_dz_interval_inverts_the_noncentral_t() -> None:
    low, high = dz_ci(2.5, 12)
    assert stats.nct.cdf(2.5, 11, low * math.sqrt(12)) == pytest.approx(0.975, abs=1e-9)
    assert stats.nct.cdf(2.5, 11, high * math.sqrt(12)) == pytest.approx(0.025, abs=1e-9)
    assert all(math.isfinite(v) for v in dz_ci(40.0, 4))
    assert all(math.isnan(v) for v in dz_ci(math.nan, 10))


def test_partial_eta_interval_matches_effectsize() -> None:
    # R effectsize's tests (test-convert_statistic.R): F_to_eta2(4, 3, 123) has a one-sided 95% lower bound of
    # 0.014 (the lower bound of our two-sided 90% interval), F_to_eta2(3.23, 1, 137) a lower bound of 0.
    assert round(partial_eta2_ci(4, 3, 123)[0], 3) == 0.014
    assert partial_eta2_ci(3.23, 1, 137)[0] == 0.0


def test_partial_eta_interval_inverts_the_noncentral_f() -> None:
    low, high = partial_eta2_ci(6.0, 2, 30)
    lam_low, lam_high = (30 * v / (1 - v) for v in (low, high))
    assert stats.ncf.cdf(6.0, 2, 30, lam_low) == pytest.approx(0.95, abs=1e-8)
    assert stats.ncf.cdf(6.0, 2, 30, lam_high) == pytest.approx(0.05, abs=1e-8)
    assert low < 6.0 * 2 / (6.0 * 2 + 30) < high


def test_percentile_interval_ignores_a_few_undefined_resamples() -> None:
    samples = np.r_[np.linspace(0, 1, 101), [np.nan] * 5]
    assert percentile_interval(samples, 0.90) == pytest.approx((0.05, 0.95))
    assert all(math.isnan(v) for v in percentile_interval(np.full(10, np.nan)))
