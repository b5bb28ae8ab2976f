"""Cell descriptives with within-subject confidence intervals (Cousineau 2005; Morey 2008).

Between-subject CIs are the wrong error bars for a repeated-measures design: they include the
subject variance that the ANOVA removes. Cousineau (2005) removes it by normalising each value,

    y'_sj = y_sj - mean_j(y_sj) + mean(y),

(subject s, within cell j, the subject mean taken over all C cells of the design). Morey (2008)
showed that the variance of the normalised values is too small by the factor (C-1)/C, so

    se_ws_j = sd(y'_.j) / sqrt(n) * sqrt(C / (C-1)),
    CI_j    = mean(y_.j) ± t_{1-α/2, n-1} · se_ws_j,

with n the number of subjects and sd the sample standard deviation (n-1 denominator) over subjects.
``sd`` in the output is the ordinary between-subject sample SD of the raw cell values.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import pandas as pd
from scipy import stats

from analysis.preparation.cells import factor_levels, require_complete

DESCRIPTIVE_STATS = ["n", "mean", "sd", "se_ws", "ci95_low", "ci95_high"]


def cell_descriptives(
    df: pd.DataFrame, dv: str, within: Sequence[str], subject: str
) -> pd.DataFrame:
    """Per-cell ``n, mean, sd, se_ws, ci95_low, ci95_high`` of ``dv`` (Cousineau–Morey 95 % CI).

    ``df`` must be complete (every subject in every cell, see ``analysis.preparation.cells``). Rows follow the
    design order of the within factors (first factor slowest); columns are the within factors
    followed by ``n, mean, sd, se_ws, ci95_low, ci95_high``.
    """
    within = list(within)
    require_complete(df, dv, within, subject)
    values = df[[subject, *within, dv]].copy()
    values[dv] = values[dv].astype(float)
    n_cells = math.prod(len(factor_levels(df, factor)) for factor in within)
    subject_mean = values.groupby(subject, observed=True)[dv].transform("mean")
    values["_normalised"] = values[dv] - subject_mean + values[dv].mean()
    morey = math.sqrt(n_cells / (n_cells - 1))

    rows = []
    for cell, group in values.groupby(within, sort=False, observed=True):
        n = len(group)
        mean = float(group[dv].mean())
        se_ws = float(group["_normalised"].std(ddof=1)) / math.sqrt(n) * morey
        half = float(stats.t.ppf(0.975, n - 1)) * se_ws
        rows.append(
            {
                **dict(zip(within, cell, strict=True)),
                "n": n,
                "mean": mean,
                "sd": float(group[dv].std(ddof=1)),
                "se_ws": se_ws,
                "ci95_low": mean - half,
                "ci95_high": mean + half,
            }
        )
    out = pd.DataFrame(rows, columns=[*within, *DESCRIPTIVE_STATS])
    return _in_design_order(out, df, within)


def _in_design_order(out: pd.DataFrame, df: pd.DataFrame, within: list[str]) -> pd.DataFrame:
    order = {f: {level: i for i, level in enumerate(factor_levels(df, f))} for f in within}
    keys = out[within].apply(lambda row: tuple(order[f][row[f]] for f in within), axis=1)
    return out.loc[keys.sort_values(kind="stable").index].reset_index(drop=True)
