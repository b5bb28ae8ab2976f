"""Residual normality of a repeated-measures ANOVA: the Shapiro–Wilk test on the model's residuals.

The residual of participant s in cell c is e_sc = y_sc − ȳ_s· − ȳ_·c + ȳ (the participant's and the cell's
means removed: what the error terms of the ANOVA are built from). The Shapiro & Wilk (1965) W and p of all n·C
residuals come from scipy. With small samples the test has little power and with large ones it flags harmless
departures; the report shows it as a check, with the plots, not as a gate.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import stats

NORMALITY_COLUMNS = ["measure", "n_residuals", "W", "p", "note"]


@dataclass(frozen=True, slots=True)
class Normality:
    n_residuals: int
    w: float = math.nan
    p: float = math.nan
    note: str = ""


def residuals(values: np.ndarray) -> np.ndarray:
    """The n × C residuals of the additive participant + cell model."""
    residuals: np.ndarray = (values - values.mean(axis=1, keepdims=True) - values.mean(axis=0, keepdims=True)
                             + values.mean())
    return residuals


def residual_normality(values: np.ndarray) -> Normality:
    """Shapiro–Wilk of the residuals of the n × C matrix ``values`` (cells in design order)."""
    e = residuals(values).ravel()
    if e.size < 3:
        return Normality(e.size, note="not testable: fewer than 3 residuals")
    if np.ptp(e) <= 1e-12 * max(float(np.abs(values).max()), 1.0):
        return Normality(e.size, note="not testable: the residuals are all zero")
    result = stats.shapiro(e)
    return Normality(e.size, float(result.statistic), float(result.pvalue))
