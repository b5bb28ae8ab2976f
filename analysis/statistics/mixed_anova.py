"""Mixed (split-plot) ANOVA: one factor between participants, one to three within, with the within part's sphericity.

The participants' cell values Y (N × C, cells in design order) are regressed on the between design X (an intercept
and G − 1 sum-to-zero codes of the G groups), once per effect on the contrast scores Z = Y L (:mod:`analysis.
sphericity`). With B = (XᵀX)⁻¹XᵀZ and the residual SSCP matrix E = (Z − XB)ᵀ(Z − XB) on N − G df, a hypothesis
K B = 0 has the SSCP H = (KB)ᵀ (K(XᵀX)⁻¹Kᵀ)⁻¹ (KB), and the univariate test of the effect is

    F = (tr H / (q d)) / (tr E / ((N − G) d))   on (q d, (N − G) d) df,

q the rows of K, d the columns of L (the univariate tests of R's ``car::Anova`` on a multivariate linear model,
which ``afex::aov_car`` reports). The effects:

* the between factor: L = 1/√C (the participants' scaled means), K the G − 1 group codes;
* a within effect W: L = L_W, K = the intercept row;
* the interaction between × W: L = L_W, K the group codes.

Sums of squares of type III (``ss_type=3``, the default, as ``afex``): every hypothesis in the full model above, so
a within effect is tested on the unweighted mean of the group means. Type II (``ss_type=2``, as ``pingouin``'s
``mixed_anova`` and ``afex``/``car`` with ``type = 2``): a within effect is tested in the model without the
interaction with the between factor, which contains it, i.e. on the participants' grand mean, H = N z̄ z̄ᵀ
(weighted by the group sizes). The between effect and the interactions are the same in both types, and with
equal groups so are the within effects.

With equal groups these are the textbook split-plot sums of squares (Maxwell & Delaney 2004, ch. 12 and 14;
``tests/analysis/statistics/test_mixed_anova.py`` computes them the textbook way too). Sphericity of a within effect
(and its interaction with the between factor) comes from the pooled within-group covariance E / (N − G)
(:func:`analysis.statistics.sphericity.covariance_sphericity`), and the reading rule is the one of
:mod:`analysis.statistics.anova`. Generalized η² (Olejnik & Algina 2003, all factors manipulated, as ``afex``):
SS_effect / (SS_effect + SS_S/B + Σ every within effect's error SS).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import pandas as pd
from scipy import stats

from analysis.statistics.anova import ANOVA_COLUMNS, _sphericity_columns, _untestable, effect_name, effects_of
from analysis.statistics.effect_sizes import BOOTSTRAP_RESAMPLES, partial_eta2_ci, percentile_interval
from analysis.statistics.sphericity import Sphericity, covariance_sphericity, effect_contrasts


def group_codes(groups: Sequence[int], n_groups: int) -> np.ndarray:
    """The N × G design: an intercept and G − 1 sum-to-zero (effect) codes; ``groups[s]`` is 0..G−1."""
    x = np.zeros((len(groups), n_groups))
    x[:, 0] = 1.0
    for s, g in enumerate(groups):
        if g < n_groups - 1:
            x[s, 1 + g] = 1.0
        else:
            x[s, 1:] = -1.0
    return x


SS_TYPES = (2, 3)
"""The sums of squares the mixed ANOVA computes (see the module docstring); 3 is the default."""


def hypothesis_ss(x: np.ndarray, z: np.ndarray, rows: np.ndarray, grand_mean: bool = False
                  ) -> tuple[float, float, np.ndarray]:
    """``(tr H, tr E, E)`` of the hypothesis ``rows`` B = 0 for responses ``z`` (N × d) on the design ``x``; with
    ``grand_mean`` (a within effect of type II) H is N z̄ z̄ᵀ instead."""
    xtx_inv = np.linalg.pinv(x.T @ x)
    beta = xtx_inv @ x.T @ z
    residual = z - x @ beta
    error = residual.T @ residual
    if grand_mean:
        return len(z) * float(z.mean(axis=0) @ z.mean(axis=0)), float(np.trace(error)), error
    kb = rows @ beta
    h = kb.T @ np.linalg.pinv(rows @ xtx_inv @ rows.T) @ kb
    return float(np.trace(h)), float(np.trace(error)), error


def check_ss_type(ss_type: int) -> None:
    if ss_type not in SS_TYPES:
        raise ValueError(f"sums of squares of type {ss_type}: the mixed ANOVA computes type 2 or 3")


def mixed_anova_table(values: np.ndarray, groups: Sequence[int], n_groups: int, levels: Sequence[int],
                      within: Sequence[str], between: str, intervals: bool = True, ss_type: int = 3
                      ) -> pd.DataFrame:
    """The ANOVA rows (``ANOVA_COLUMNS``) of participants × cells ``values`` whose between level is ``groups[s]``:
    the between effect, then each within effect followed by its interaction with the between factor, with sums of
    squares of ``ss_type`` (2 or 3). Without ``intervals`` the partial η² intervals are left empty."""
    check_ss_type(ss_type)
    n, n_cells = values.shape
    dof = n - n_groups
    total = float(((values - values.mean()) ** 2).sum())
    (ss_b, ss_sb), within_parts = _sums(values, groups, n_groups, levels, within, ss_type)
    error_total = ss_sb + sum(part[4] for part in within_parts)
    spherical = Sphericity(1, math.nan, math.nan, math.nan, math.nan, 1.0, 1.0)
    rows = [_row(between, n_groups - 1, dof, ss_b, ss_sb, total, error_total, spherical, intervals)]
    for name, d, ss_w, ss_bw, ss_err, error in within_parts:
        s = covariance_sphericity(error / dof if dof > 0 else error, dof, n_cells)
        rows.append(_row(name, d, d * dof, ss_w, ss_err, total, error_total, s, intervals))
        rows.append(_row(f"{between} * {name}", (n_groups - 1) * d, d * dof, ss_bw, ss_err, total, error_total, s,
                         intervals))
    return pd.DataFrame(rows, columns=ANOVA_COLUMNS)


def mixed_ges_bootstrap(values: np.ndarray, groups: Sequence[int], n_groups: int, levels: Sequence[int],
                        within: Sequence[str], rng: np.random.Generator,
                        resamples: int = BOOTSTRAP_RESAMPLES, ss_type: int = 3) -> list[tuple[float, float]]:
    """Percentile intervals of each effect's η²G (rows in :func:`mixed_anova_table` order): participants drawn with
    replacement within their group, so every resample keeps the groups' sizes. The groups' sizes being fixed, every
    resample has the same design, so the sums of squares of all resamples are computed at once (the same sums as
    :func:`_sums`, one resample per row)."""
    labels = np.asarray(groups)
    members = [np.flatnonzero(labels == g) for g in range(n_groups)]
    picks = np.concatenate([m[rng.integers(0, len(m), size=(resamples, len(m)))] for m in members], axis=1)
    x = group_codes(np.concatenate([np.full(len(m), g) for g, m in enumerate(members)]).tolist(), n_groups)
    stack = values[picks]  # resamples × participants × cells
    intercept, codes = np.eye(n_groups)[:1], np.eye(n_groups)[1:]
    ss_b, ss_sb = _stacked_ss(x, stack @ effect_contrasts(levels, ()), codes)
    ss, error_total = [ss_b], ss_sb
    for effect in effects_of(within):
        z = stack @ effect_contrasts(levels, effect)
        ss_w, ss_err = _stacked_ss(x, z, intercept, grand_mean=ss_type == 2)
        ss += [ss_w, _stacked_ss(x, z, codes)[0]]
        error_total = error_total + ss_err
    hypothesis = np.stack(ss, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        ges = hypothesis / (hypothesis + error_total[:, None])
    return [percentile_interval(column) for column in ges.T]


def _stacked_ss(x: np.ndarray, z: np.ndarray, rows: np.ndarray, grand_mean: bool = False
                ) -> tuple[np.ndarray, np.ndarray]:
    """:func:`hypothesis_ss`'s ``(tr H, tr E)`` for a stack of responses ``z`` (resamples × N × d) on one design."""
    xtx_inv = np.linalg.pinv(x.T @ x)
    fit = xtx_inv @ x.T
    residual = z - x @ (fit @ z)
    error = (residual ** 2).sum(axis=(1, 2))
    if grand_mean:
        mean = z.mean(axis=1)
        return z.shape[1] * (mean ** 2).sum(axis=1), error
    kb = (rows @ fit) @ z
    middle = np.linalg.pinv(rows @ xtx_inv @ rows.T)
    return np.einsum("rqd,qp,rpd->r", kb, middle, kb), error


def _sums(values: np.ndarray, groups: Sequence[int], n_groups: int, levels: Sequence[int], within: Sequence[str],
          ss_type: int) -> tuple[tuple[float, float], list[tuple[str, int, float, float, float, np.ndarray]]]:
    """``(SS_between, SS_S/B)`` and, per within effect, ``(name, d, SS_W, SS_B×W, SS_error, error SSCP)``."""
    x = group_codes(groups, n_groups)
    intercept, codes = np.eye(n_groups)[:1], np.eye(n_groups)[1:]
    ss_b, ss_sb, _ = hypothesis_ss(x, values @ effect_contrasts(levels, ()), codes)
    parts = []
    for effect in effects_of(within):
        contrast = effect_contrasts(levels, effect)
        z = values @ contrast
        ss_w, ss_err, error = hypothesis_ss(x, z, intercept, grand_mean=ss_type == 2)
        parts.append((effect_name(within, effect), contrast.shape[1], ss_w, hypothesis_ss(x, z, codes)[0], ss_err,
                      error))
    return (ss_b, ss_sb), parts


def _row(name: str, df1: int, df2: int, ss: float, ss_err: float, total: float, error_total: float,
         s: Sphericity, interval: bool) -> dict[str, object]:
    note = "not testable: fewer participants than groups + 1" if df2 <= 0 else _untestable(
        df2 + 2, ss, ss_err, total)
    f_value = math.nan if note else (ss / df1) / (ss_err / df2)
    low, high = partial_eta2_ci(f_value, df1, df2) if interval and not note else (math.nan, math.nan)
    row: dict[str, object] = {
        "effect": name, "df1": df1, "df2": df2, "SS": ss, "SS_error": ss_err, "MS": ss / df1,
        "MSE": ss_err / df2 if df2 > 0 else math.nan, "F": f_value,
        "p": math.nan if note else float(stats.f.sf(f_value, df1, df2)),
        "ges": ss / (ss + error_total) if ss + error_total > 0 else math.nan,
        "partial_eta2": ss / (ss + ss_err) if ss + ss_err > 0 else math.nan,
        "partial_eta2_ci_low": low, "partial_eta2_ci_high": high, "note": note,
    }
    row.update(_sphericity_columns(row, s))
    return row
