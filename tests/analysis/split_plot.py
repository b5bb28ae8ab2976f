"""The split-plot sums of squares computed the textbook way, independently of analysis.statistics.mixed_anova: the
check of the mixed ANOVA (tests/analysis/statistics/test_mixed_anova.py) and of what SPSS would compute from
``wide.sav`` (tests/analysis/pipeline/test_analyze_stored_designs.py)."""

from __future__ import annotations

import itertools

import numpy as np
import pandas as pd


def textbook(long: pd.DataFrame, dv: str, between: str, within: list[str],
             subject: str) -> dict[str, tuple[float, float, int, int]]:
    """Split-plot sums of squares from marginal means (each effect's inclusion–exclusion residual, summed over all
    observations); subject ids are unique, so S/A = S − A and S/A × W = S × W − A × W (equal groups)."""
    def ss(term: tuple[str, ...]) -> float:
        total = pd.Series(0.0, index=long.index)
        for size in range(len(term) + 1):
            for part in itertools.combinations(term, size):
                means = (long.groupby(list(part))[dv].transform("mean") if part else
                         pd.Series(long[dv].mean(), index=long.index))
                total += (-1) ** (len(term) - size) * means
        return float((total ** 2).sum())

    n_subjects, n_groups = long[subject].nunique(), long[between].nunique()
    levels = {f: long[f].nunique() for f in within}
    out = {between: (ss((between,)), ss((subject,)) - ss((between,)), n_groups - 1, n_subjects - n_groups)}
    for size in range(1, len(within) + 1):
        for effect in itertools.combinations(within, size):
            d = int(np.prod([levels[f] - 1 for f in effect]))
            error = ss((subject, *effect)) - ss((between, *effect))
            df2 = d * (n_subjects - n_groups)
            out[" * ".join(effect)] = (ss(effect), error, d, df2)
            out[f"{between} * {' * '.join(effect)}"] = (ss((between, *effect)), error, (n_groups - 1) * d, df2)
    return out
