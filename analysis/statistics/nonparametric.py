"""Rank tests beside the ANOVA, for rating measures (questionnaire items and scales, which are ordinal).

For each within factor, on the participants' marginal means at its levels (their mean over the other
factors' cells): the Wilcoxon signed-rank test for two levels, the Friedman test beyond (Hollander & Wolfe
1973); with more than one factor, also the Friedman test across all conditions. Conventions follow R's
``wilcox.test`` / ``friedman.test``: zero differences are dropped, the statistic V is the sum of the ranks of the
positive differences (level_1 − level_2), the p value is exact below 50 pairs without ties or zeros and
otherwise from the normal approximation with tie and continuity corrections (scipy). Effect sizes: the
matched-pairs rank-biserial correlation (Kerby 2014) for Wilcoxon, Kendall's W for Friedman (both pingouin).

Ranks are taken of values rounded to the measure's resolution: a marginal mean of m cells of a measure whose values
are multiples of r (1 for a rating item, 1/k for the mean of k items) is a multiple of r/m, and is rounded to that
grid before ranking: the tests run on the whole number of grid steps (the item sums, up to a constant factor,
which changes no rank). Otherwise floating-point noise (4.833333333333334 against 4.833333333333333, two orders of
summing the same answers) would rank as a difference and break ties (:func:`on_grid`).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pandas as pd
from scipy import stats

from analysis.preparation.cells import design_cells, factor_levels
from analysis.source.naming import cell_label

RANK_TEST_COLUMNS = ["factor", "test", "levels", "n", "statistic", "df", "p", "effect_size", "effect_size_name",
                     "note"]
ALL_CONDITIONS = "all conditions"


def rank_tests(df: pd.DataFrame, dv: str, within: Sequence[str], subject: str,
               resolution: float | None = None) -> pd.DataFrame:
    """One row per factor (and one for all conditions when there are several factors). ``df`` is complete;
    ``resolution`` is the step of the measure's values (see the module docstring)."""
    within = list(within)
    rows = []
    n_cells = int(np.prod([len(factor_levels(df, f)) for f in within]))
    for factor in within:
        means = df.groupby([subject, factor], observed=True)[dv].mean().unstack(factor)[factor_levels(df, factor)]
        averaged = n_cells // means.shape[1]
        rows.append({"factor": factor, **_test(on_grid(means, resolution, averaged))})
    if len(within) > 1:
        order = [cell_label(within, cell) for cell in design_cells(df, within)]
        cells = df.assign(_cell=[cell_label(within, tuple(r)) for r in df[within].itertuples(index=False)])
        wide = cells.pivot_table(index=subject, columns="_cell", values=dv, observed=True)[order]
        rows.append({"factor": ALL_CONDITIONS, **_test(on_grid(wide, resolution, 1))})
    return pd.DataFrame(rows, columns=RANK_TEST_COLUMNS)


def on_grid(wide: pd.DataFrame, resolution: float | None, averaged: int) -> pd.DataFrame:
    """``wide`` (means of ``averaged`` values each) as whole numbers of steps ``resolution / averaged`` (every
    statistic here depends on ranks only), or rounded to 9 decimals when the resolution is unknown."""
    if resolution is None:
        return wide.round(9)
    return (wide * (averaged / resolution)).round()


def _test(wide: pd.DataFrame) -> dict[str, object]:
    values = wide.to_numpy(dtype=float)
    n, k = values.shape
    levels = " vs ".join(str(c) for c in wide.columns)
    base: dict[str, object] = {"levels": levels, "n": n}
    if k == 2:
        return {**base, **wilcoxon_signed_rank(values[:, 0], values[:, 1])}
    return {**base, **friedman(wide)}


def wilcoxon_signed_rank(x: np.ndarray, y: np.ndarray) -> dict[str, object]:
    """V (sum of positive ranks of x − y), df, p (two-sided) and the rank-biserial correlation."""
    import pingouin as pg

    out: dict[str, object] = {"test": "Wilcoxon signed-rank", "df": np.nan, "effect_size_name": "rank-biserial r"}
    diff = x - y
    nonzero = diff[diff != 0]
    if nonzero.size == 0:
        return {**out, "statistic": np.nan, "p": np.nan, "effect_size": np.nan,
                "note": "not testable: every participant has the same value at both levels"}
    ranks = stats.rankdata(np.abs(nonzero))
    result = pg.wilcoxon(x, y, correction=True)
    return {**out, "statistic": float(ranks[nonzero > 0].sum()), "p": float(result["p_val"].iloc[0]),
            "effect_size": float(result["RBC"].iloc[0]), "note": ""}


def friedman(wide: pd.DataFrame) -> dict[str, object]:
    """Friedman's χ² (tie-corrected), df, p and Kendall's W of a subjects × conditions table."""
    import pingouin as pg

    out: dict[str, object] = {"test": "Friedman", "effect_size_name": "Kendall's W"}
    values = wide.to_numpy(dtype=float)
    if np.all(values == values[:, :1]):
        return {**out, "statistic": np.nan, "df": values.shape[1] - 1, "p": np.nan, "effect_size": np.nan,
                "note": "not testable: every participant gives the same value in every condition"}
    long = wide.reset_index(drop=True).rename_axis("_subject").reset_index().melt(
        id_vars="_subject", var_name="_level", value_name="_y")
    result = pg.friedman(data=long, dv="_y", within="_level", subject="_subject")
    return {**out, "statistic": float(result["Q"].iloc[0]), "df": int(result["ddof1"].iloc[0]),
            "p": float(result["p_unc"].iloc[0]), "effect_size": float(result["W"].iloc[0]), "note": ""}
