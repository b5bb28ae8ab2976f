"""``ticks`` is censored at the horizon: the trials that reached it, and the analysis of ``finished``.

A trial that did not deliver every order stops at the horizon, so its ``ticks`` is the horizon, not the time
the team would have needed: the value is right-censored (docs/analysis.md "Measures"). Per cell the report
gives the share of trials that reached the horizon (``finished`` = 0) and a note for each censored cell, and
``finished`` itself is compared between conditions with tests for paired binary outcomes:

* two conditions: McNemar's test, exact (the binomial test on the discordant pairs; statsmodels), the right
  choice for the small samples of a user study (Fagerland, Lydersen & Laake 2013);
* more conditions: Cochran's (1950) Q (pingouin).

The tests run across all conditions and, for every factor, within each combination of the other factors'
levels (the simple effects of the ANOVA's follow-ups).
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence

import numpy as np
import pandas as pd

from analysis.preparation.cells import factor_levels, slices
from analysis.source.naming import cell_label

CENSORED_MEASURES = ("ticks",)
"""Measures capped at the horizon when a trial does not finish."""
CENSORING_COLUMNS = ["cell", "n", "reached_horizon", "share"]
FINISHED_COLUMNS = ["factor", "at", "test", "n", "statistic", "df", "p", "note"]


def censoring_table(df: pd.DataFrame, within: Sequence[str], finished: str = "finished") -> pd.DataFrame:
    """Per cell (design order): trials, trials that reached the horizon (``finished`` = 0) and their share."""
    within = list(within)
    rows = []
    for cell in itertools.product(*(factor_levels(df, f) for f in within)):
        mask = np.logical_and.reduce([df[f] == level for f, level in zip(within, cell, strict=True)])
        values = df.loc[mask, finished].dropna()
        reached = int((values == 0).sum())
        rows.append({"cell": cell_label(within, cell), "n": len(values), "reached_horizon": reached,
                     "share": reached / len(values) if len(values) else np.nan})
    return pd.DataFrame(rows, columns=CENSORING_COLUMNS)


def censoring_note(table: pd.DataFrame, measure: str) -> str:
    """The report's note for a censored measure, or ``""`` when no trial reached the horizon."""
    censored = table[table["reached_horizon"] > 0]
    if measure not in CENSORED_MEASURES or censored.empty:
        return ""
    cells = "; ".join(f"{r.cell}: {r.reached_horizon} of {r.n}" for r in censored.itertuples())
    return (f"{measure} is censored at the horizon in {len(censored)} cell(s) ({cells} trials reached it): those "
            "values are the horizon, not the time the team needed, so differences involving these cells are "
            "underestimated; read the analysis of finished beside it.")


def finished_tests(df: pd.DataFrame, within: Sequence[str], subject: str, finished: str = "finished"
                   ) -> pd.DataFrame:
    """McNemar / Cochran's Q across all conditions and, per factor, within each cell of the other factors."""
    within = list(within)
    rows = [{"factor": "all conditions", "at": "", **_compare(df, within, subject, finished)}]
    for factor in within if len(within) > 1 else []:
        rows += [{"factor": factor, "at": label, **_compare(part, [factor], subject, finished)}
                 for label, part in slices(df, within, factor)]
    return pd.DataFrame(rows, columns=FINISHED_COLUMNS)


def _compare(df: pd.DataFrame, within: list[str], subject: str, finished: str) -> dict[str, object]:
    labels = [cell_label(within, tuple(r)) for r in df[within].itertuples(index=False)]
    wide = df.assign(_cell=labels).pivot_table(index=subject, columns="_cell", values=finished, observed=True,
                                               sort=False).dropna()
    n, k = wide.shape
    test = "McNemar (exact)" if k == 2 else "Cochran's Q"
    out: dict[str, object] = {"test": test, "n": n, "statistic": np.nan, "df": np.nan, "p": np.nan, "note": ""}
    values = wide.to_numpy(dtype=float)
    if n < 2 or np.all(values == values[0, 0]):
        state = "finished" if n and values[0, 0] == 1 else "reached the horizon"
        out["note"] = "not testable: fewer than 2 participants" if n < 2 else f"not testable: every trial {state}"
        return out
    if np.all(values == values[:, :1]):
        out["note"] = "not testable: every participant finished in all of these conditions or in none"
        return out
    if k == 2:
        from statsmodels.stats.contingency_tables import mcnemar

        table = pd.crosstab(values[:, 0], values[:, 1]).reindex(index=[0, 1], columns=[0, 1], fill_value=0)
        result = mcnemar(table.to_numpy(), exact=True)
        return {**out, "statistic": float(result.statistic), "p": float(result.pvalue)}
    import pingouin as pg

    long = wide.reset_index(drop=True).rename_axis("_s").reset_index().melt(id_vars="_s", value_name="_y")
    result = pg.cochran(data=long, dv="_y", within="_cell", subject="_s")
    return {**out, "statistic": float(result["Q"].iloc[0]), "df": int(result["dof"].iloc[0]),
            "p": float(result["p_unc"].iloc[0])}
