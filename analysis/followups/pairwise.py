"""Pairwise paired comparisons of the levels of each factor with more than two levels.

Each participant's marginal mean at a level (the mean of their cells at that level, over the other factors; ``at``
empty) is compared between every pair of levels with a paired t test on n − 1 df (the unpooled error of each comparison,
as JASP and ``emmeans``' multivariate option do). With more than one factor the same comparisons are made within each
combination of the other factors' levels (``at``: ``kitchen=none_3``), on the participants' values in that slice: what a
significant interaction calls for. Reported per pair: the mean difference (level_1 − level_2) with its 95 % CI (not
adjusted for multiplicity), t, p and the Holm-adjusted p within its family (Holm 1979): the comparisons of one factor at
one ``at``, and Cohen's d_z = mean difference / SD of the differences (Cohen 1988, p. 48; Lakens 2013) with its exact 95
% CI from the noncentral t (:mod:`analysis.statistics.effect_sizes`). d_z is the standardised effect the paired test
itself estimates; divide by √(2(1 − r)) for a d on the scale of the raw SD (Lakens 2013, eq. 9).

These are the comparisons of a design within participants (one group: ``emmeans``' multivariate model is this paired
t). In a mixed design ``emmeans`` pools the covariance over the groups instead;
:mod:`analysis.followups.mixed_followups` does that by default (:mod:`analysis.followups.pooled_followups`) and uses
these per-group tests only with ``per-group``.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence

import pandas as pd

from analysis.followups.paired import paired_difference
from analysis.followups.simple_effects import holm
from analysis.preparation.cells import factor_levels, slices

PAIRWISE_COLUMNS = [
    "factor", "at", "level_1", "level_2", "n", "mean_1", "mean_2", "mean_diff", "se", "ci95_low", "ci95_high",
    "t", "df", "p", "p_holm", "dz", "dz_ci_low", "dz_ci_high", "note",
]


def pairwise_comparisons(df: pd.DataFrame, dv: str, within: Sequence[str], subject: str) -> pd.DataFrame:
    """Rows for every pair of levels of every factor with more than two levels, on the marginal means and then
    within each level (combination) of the other factors (empty when no factor has more than two levels)."""
    blocks = []
    for factor in within:
        levels = factor_levels(df, factor)
        if len(levels) < 3:
            continue
        families = [("", df), *(slices(df, within, factor) if len(within) > 1 else [])]
        for at, part in families:
            means = part.groupby([subject, factor], observed=True)[dv].mean().unstack(factor)[levels]
            block = pd.DataFrame([_pair(factor, means, a, b) for a, b in itertools.combinations(levels, 2)])
            block["at"] = at
            block["p_holm"] = holm(block["p"])
            blocks.append(block)
    if not blocks:
        return pd.DataFrame(columns=PAIRWISE_COLUMNS)
    return pd.concat(blocks, ignore_index=True)[PAIRWISE_COLUMNS]


def _pair(factor: str, means: pd.DataFrame, a: object, b: object) -> dict[str, object]:
    x, y = means[a].to_numpy(dtype=float), means[b].to_numpy(dtype=float)
    return {"factor": factor, "level_1": a, "level_2": b, "mean_1": float(x.mean()), "mean_2": float(y.mean()),
            **paired_difference(x, y)}
