"""The paired difference of two samples (the same participants measured twice): what a two-level simple effect
and each pairwise comparison report beside their test."""

from __future__ import annotations

import math

import numpy as np
from scipy import stats

from analysis.statistics.effect_sizes import dz_ci


def paired_difference(x: np.ndarray, y: np.ndarray) -> dict[str, float | str]:
    """Mean difference x − y, its SE and 95 % CI, t, df, two-sided p and d_z with its CI."""
    diff = np.asarray(x, dtype=float) - np.asarray(y, dtype=float)
    n = len(diff)
    nan = math.nan
    out: dict[str, float | str] = {"n": n, "mean_diff": float(diff.mean()) if n else nan, "note": ""}
    sd = float(diff.std(ddof=1)) if n > 1 else nan
    if n < 2 or not sd > 0:
        out.update(se=nan, ci95_low=nan, ci95_high=nan, t=nan, df=max(n - 1, 0), p=nan, dz=nan,
                   dz_ci_low=nan, dz_ci_high=nan)
        out["note"] = ("not testable: fewer than 2 participants" if n < 2 else
                       "not testable: every participant has the same difference")
        return out
    result = stats.ttest_rel(x, y)
    ci = result.confidence_interval(0.95)
    t = float(result.statistic)
    low, high = dz_ci(t, n)
    out.update(se=sd / math.sqrt(n), ci95_low=float(ci.low), ci95_high=float(ci.high), t=t, df=n - 1,
               p=float(result.pvalue), dz=float(diff.mean()) / sd, dz_ci_low=low, dz_ci_high=high)
    return out
