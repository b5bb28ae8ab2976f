"""Confidence intervals for effect sizes.

* Partial η², from the observed F(df1, df2): the noncentrality λ of a noncentral F is found for which the
  observed F is the (1 + level)/2 and the (1 − level)/2 quantile (Steiger 2004, "Beyond the F test",
  Psychological Methods 9(2)), and each bound is converted with η²p = λ / (λ + df2), the conversion of R's
  ``effectsize`` (Ben-Shachar, Lüdecke & Makowski 2020), which maps λ = F·df1 to the point estimate
  F·df1 / (F·df1 + df2). The default level is 90 %: its lower bound is the one-sided 95 % bound that matches a
  test at α = .05 (Steiger 2004).
* Cohen's d_z = mean difference / SD of the differences (paired designs, Cohen 1988 p. 48), with the exact
  interval from the noncentral t: δ with t_obs at the (1 ± level)/2 quantiles of t(n − 1, δ), d = δ / √n
  (Cumming & Finch 2001).
* Generalized η² has no exact interval; it is bootstrapped by resampling participants with replacement
  (percentile interval), every resample analysed with the same contrasts as the ANOVA
  (:mod:`analysis.statistics.anova`).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from scipy import optimize, stats

ETA_CI_LEVEL = 0.90
"""Level of the intervals for η²p and η²G (see the module docstring)."""
BOOTSTRAP_RESAMPLES = 2000


def partial_eta2_ci(f_value: float, df1: float, df2: float, level: float = ETA_CI_LEVEL) -> tuple[float, float]:
    """``(low, high)`` of partial η² from a noncentral-F interval for λ; NaN when F is not finite."""
    if not (math.isfinite(f_value) and df1 > 0 and df2 > 0):
        return (math.nan, math.nan)
    tail = (1 - level) / 2

    def cdf(lam: float) -> float:
        return float(stats.f.cdf(f_value, df1, df2) if lam == 0 else stats.ncf.cdf(f_value, df1, df2, lam))

    low, high = (1.0 if math.isinf(lam) else lam / (lam + df2)
                 for lam in (_decreasing_root(cdf, 1 - tail), _decreasing_root(cdf, tail)))
    return (low, high)


def dz_ci(t_value: float, n: int, level: float = 0.95, df: int | None = None) -> tuple[float, float]:
    """``(low, high)`` of Cohen's d_z for a paired t on n pairs (noncentral-t inversion); NaN where the noncentral
    t cannot be evaluated. ``df`` is the t's degrees of freedom when its SD is not the n pairs' own (n − 1): N − G
    for the pooled within-group SD of a mixed design's follow-ups (:mod:`analysis.followups.pooled_followups`)."""
    df = n - 1 if df is None else df
    if not (math.isfinite(t_value) and n >= 1 and df >= 1):
        return (math.nan, math.nan)
    tail = (1 - level) / 2

    def cdf(delta: float) -> float:
        value = float(stats.nct.cdf(t_value, df, delta))
        return value if math.isfinite(value) else 1.0 - float(stats.nct.sf(t_value, df, delta))

    low, high = (_delta_root(cdf, target, t_value) for target in (1 - tail, tail))
    return (low / math.sqrt(n), high / math.sqrt(n))


def _delta_root(cdf: Callable[[float], float], target: float, start: float) -> float:
    """The δ with cdf(δ) = target for a cdf decreasing in δ, bracketed outwards from ``start``."""
    step = 1.0 + abs(start)
    low, high = start - step, start + step
    for _ in range(60):
        if cdf(low) >= target:
            break
        low -= step
        step *= 2
    step = 1.0 + abs(start)
    for _ in range(60):
        if cdf(high) <= target:
            break
        high += step
        step *= 2
    f_low, f_high = cdf(low) - target, cdf(high) - target
    if not (math.isfinite(f_low) and math.isfinite(f_high)) or f_low < 0 or f_high > 0:
        return math.nan
    try:
        return float(optimize.brentq(lambda x: cdf(x) - target, low, high, xtol=1e-12))
    except ValueError:
        return math.nan


def percentile_interval(samples: np.ndarray, level: float = ETA_CI_LEVEL) -> tuple[float, float]:
    """The percentile bootstrap interval of the finite ``samples`` (NaN when fewer than half are finite)."""
    finite = samples[np.isfinite(samples)]
    if finite.size < samples.size / 2:
        return (math.nan, math.nan)
    tail = 100 * (1 - level) / 2
    low, high = np.percentile(finite, [tail, 100 - tail])
    return (float(low), float(high))


def resample_indices(n: int, rng: np.random.Generator, resamples: int = BOOTSTRAP_RESAMPLES) -> np.ndarray:
    """``resamples × n`` participant indices drawn with replacement."""
    return rng.integers(0, n, size=(resamples, n))


def _decreasing_root(cdf: Callable[[float], float], target: float) -> float:
    """The λ ≥ 0 with cdf(λ) = target for a cdf decreasing in λ; 0 when cdf(0) is already below target."""
    if cdf(0.0) <= target:
        return 0.0
    high = 1.0
    while cdf(high) > target:
        high *= 2
        if high > 1e7:
            return math.inf
    return float(optimize.brentq(lambda lam: cdf(lam) - target, 0.0, high))
