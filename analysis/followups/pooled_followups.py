"""Follow-ups of a mixed design on the pooled within-group covariance: the default convention, that of ``emmeans``
on an ``afex`` model (its multivariate model, ``afex_options("emmeans_model")``).

With Y the N participants × C cells (design order) of G groups, the n_g participants of group g and their cell
means ȳ_g, the pooled within-group covariance of the cells is

    S = Σ_g (Y_g − 1ȳ_g)ᵀ (Y_g − 1ȳ_g) / (N − G),

the error covariance of the mixed ANOVA (:mod:`analysis.statistics.mixed_anova`). Within group g:

* a comparison of cell weights c (a pair of levels: +1 and −1 on the two cells of a slice, or ±1/m on the m cells
  of each level for the factor's marginal means) has the estimate ȳ_g c, the standard error √(cᵀSc / n_g) and
  t on N − G df (``emmeans``' ``pairs``); Cohen's d_z is ȳ_g c / √(cᵀSc) (the pooled SD of the differences),
  its 95 % CI from the noncentral t on N − G df;
* the simple effect of a factor with contrasts C (cells × d, orthonormal over the levels, zero outside the slice)
  is the Wald test F = m̄ᵀ (CᵀSC / n_g)⁻¹ m̄ / d on (d, N − G) df, m̄ = Cᵀȳ_g (``emmeans``' ``joint_tests``; it
  assumes no sphericity, so it has no ε). With d = 1 it is the square of the comparison's t.

Between groups (a between factor with more than two levels) the participants' means over all cells are compared
with the variance pooled over all G groups, t on N − G df (``emmeans``' ``pairs`` of the between factor).
``tests/analysis/followups/test_mixed_conventions.py`` checks every one against ``emmeans`` on published datasets.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import pandas as pd
from scipy import stats

from analysis.preparation.cells import factor_levels, group_index, wide_matrix
from analysis.statistics.effect_sizes import dz_ci
from analysis.statistics.sphericity import orthonormal_contrasts

NO_ERROR_DF = "not testable: fewer participants than groups + 1"
NO_ERROR = "not testable: no error variance (every participant of every group shows the same pattern)"


@dataclass(frozen=True, slots=True, eq=False)
class PooledDesign:
    """The cells of a complete mixed design and their pooled within-group covariance."""

    values: np.ndarray
    """Participants × cells in design order."""
    groups: np.ndarray
    """Each participant's group index into ``group_names``."""
    group_names: tuple[object, ...]
    within: tuple[str, ...]
    levels: tuple[tuple[object, ...], ...]
    covariance: np.ndarray
    """S, cells × cells."""
    dof: int
    """N − G."""

    @property
    def cells(self) -> list[tuple[object, ...]]:
        return list(itertools.product(*self.levels))

    def size(self, group: int) -> int:
        return int((self.groups == group).sum())

    def means(self, group: int) -> np.ndarray:
        return np.asarray(self.values[self.groups == group].mean(axis=0))


def pooled_design(clean: pd.DataFrame, dv: str, within: Sequence[str], between: str, subject: str) -> PooledDesign:
    """The design of the complete cases ``clean`` (one level of ``between`` per participant)."""
    values, subjects = wide_matrix(clean, dv, within, subject)
    names = tuple(factor_levels(clean, between))
    groups = np.asarray(group_index(clean, subjects, between, subject, names))
    residual = values.copy()
    for g in range(len(names)):
        residual[groups == g] -= values[groups == g].mean(axis=0)
    dof = len(values) - len(names)
    covariance = residual.T @ residual / dof if dof > 0 else np.full((values.shape[1],) * 2, np.nan)
    levels = tuple(tuple(factor_levels(clean, f)) for f in within)
    return PooledDesign(values, groups, names, tuple(within), levels, covariance, dof)


def slice_weights(design: PooledDesign, factor: str, at: dict[str, object]) -> tuple[np.ndarray, list[object]]:
    """``(W, levels)``: W is cells × levels, column j averaging the cells at level j of ``factor`` among the cells
    whose other factors are at ``at`` (every level of a factor not in ``at``: marginal means)."""
    f = design.within.index(factor)
    levels = list(design.levels[f])
    weights = np.zeros((len(design.cells), len(levels)))
    for c, cell in enumerate(design.cells):
        if all(cell[design.within.index(name)] == level for name, level in at.items()):
            weights[c, levels.index(cell[f])] = 1.0
    return weights / weights.sum(axis=0, keepdims=True), levels


def pooled_simple_effect(design: PooledDesign, group: int, factor: str, at: dict[str, object]) -> dict[str, object]:
    """The test columns of the simple effect of ``factor`` in ``group`` at ``at`` (see the module docstring):
    ``df1, df2, MSE, F, p`` and, for two levels, the difference's CI and d_z."""
    weights, levels = slice_weights(design, factor, at)
    contrasts = weights @ orthonormal_contrasts(len(levels))
    d, n = contrasts.shape[1], design.size(group)
    row: dict[str, object] = {"df1": d, "df2": design.dof, "eps_gg": math.nan, "eps_hf": math.nan,
                              "correction": "none", "df1_read": d, "df2_read": design.dof, "note": ""}
    error = contrasts.T @ design.covariance @ contrasts if design.dof > 0 else None
    row["MSE"] = float(np.trace(error)) / d if error is not None else math.nan
    note = NO_ERROR_DF if error is None else NO_ERROR if not _positive_definite(error) else ""
    if note:
        return {**row, "F": math.nan, "p": math.nan, "p_read": math.nan, "note": note}
    assert error is not None
    mean = contrasts.T @ design.means(group)
    f_value = float(mean @ np.linalg.solve(error / n, mean)) / d
    p = float(stats.f.sf(f_value, d, design.dof))
    row.update(F=f_value, p=p, p_read=p)
    if len(levels) == 2:
        pair = pooled_pair(design, group, weights[:, 0] - weights[:, 1])
        row.update({k: pair[k] for k in ("mean_diff", "ci95_low", "ci95_high", "dz", "dz_ci_low", "dz_ci_high")})
    return row


def pooled_pair(design: PooledDesign, group: int, weights: np.ndarray) -> dict[str, object]:
    """A comparison of cell ``weights`` in ``group``: ``n, mean_diff, se, ci95_low, ci95_high, t, df, p, dz,
    dz_ci_low, dz_ci_high, note``."""
    n, dof = design.size(group), design.dof
    estimate = float(design.means(group) @ weights)
    nan = math.nan
    out: dict[str, object] = {"n": n, "mean_diff": estimate, "df": dof, "note": ""}
    variance = float(weights @ design.covariance @ weights) if dof > 0 else nan
    if not variance > 0:
        return {**out, "se": nan, "ci95_low": nan, "ci95_high": nan, "t": nan, "p": nan, "dz": nan,
                "dz_ci_low": nan, "dz_ci_high": nan, "note": NO_ERROR_DF if dof < 1 else NO_ERROR}
    se = math.sqrt(variance / n)
    t = estimate / se
    half = float(stats.t.ppf(0.975, dof)) * se
    low, high = dz_ci(t, n, df=dof)
    return {**out, "se": se, "ci95_low": estimate - half, "ci95_high": estimate + half, "t": t,
            "p": float(2 * stats.t.sf(abs(t), dof)), "dz": estimate / math.sqrt(variance), "dz_ci_low": low,
            "dz_ci_high": high}


def pooled_pairs(design: PooledDesign, group: int, factor: str, at: dict[str, object]) -> list[dict[str, object]]:
    """Every pair of levels of ``factor`` in ``group`` at ``at`` (the ``PAIRWISE_COLUMNS`` but ``at`` and
    ``p_holm``)."""
    weights, levels = slice_weights(design, factor, at)
    means = design.means(group) @ weights
    return [{"factor": factor, "level_1": levels[a], "level_2": levels[b], "mean_1": float(means[a]),
             "mean_2": float(means[b]), **pooled_pair(design, group, weights[:, a] - weights[:, b])}
            for a, b in itertools.combinations(range(len(levels)), 2)]


def pooled_group_pair(person_means: np.ndarray, groups: np.ndarray, a: int, b: int
                      ) -> tuple[float, int, float, float, float]:
    """``(t, df, p, CI low, CI high)`` of group a − group b on the participants' means over all cells, with the
    variance pooled over every group (N − G df)."""
    names = np.unique(groups)
    dof = len(person_means) - len(names)
    nan = math.nan
    if dof < 1:
        return nan, max(dof, 0), nan, nan, nan
    pooled = sum(float(((person_means[groups == g] - person_means[groups == g].mean()) ** 2).sum())
                 for g in names) / dof
    x, y = person_means[groups == a], person_means[groups == b]
    se = math.sqrt(pooled * (1 / len(x) + 1 / len(y)))
    if not se > 0:
        return nan, dof, nan, nan, nan
    diff = float(x.mean() - y.mean())
    half = float(stats.t.ppf(0.975, dof)) * se
    return diff / se, dof, float(2 * stats.t.sf(abs(diff / se), dof)), diff - half, diff + half


def _positive_definite(matrix: np.ndarray) -> bool:
    scale = max(float(np.trace(matrix)), 0.0)
    return bool(scale > 0 and np.linalg.eigvalsh(matrix).min() > 1e-12 * scale)
