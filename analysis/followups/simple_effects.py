"""Simple main effects: each within factor tested within every combination of the levels of the others.

In a robot × kitchen design that is the robot effect in each kitchen *and* the kitchen effect with each robot
(both directions); with three factors, the effect of each factor in each cell of the other two. Each simple
effect is a one-way repeated-measures ANOVA on the participants' values in that slice (its own error term,
Maxwell & Delaney 2004, ch. 12), with the same sphericity columns and reading rule as the omnibus table
(:mod:`analysis.statistics.anova`). The p values read are Holm-adjusted (Holm 1979) within each family: the simple
effects of one factor across the levels of the others. A factor with two levels has one comparison per slice: its row
also gives the mean difference level_1 − level_2 with its 95 % CI and Cohen's d_z with its CI (as
:mod:`analysis.followups.pairwise` computes them), so a two-level simple effect reads like a pairwise comparison.
"""

from __future__ import annotations

from collections.abc import Sequence

import pandas as pd

from analysis.followups.paired import paired_difference
from analysis.preparation.cells import factor_levels, slices
from analysis.statistics.anova import rm_anova

SIMPLE_EFFECT_COLUMNS = [
    "factor", "at", "df1", "df2", "MSE", "F", "p", "ges", "eps_gg", "eps_hf", "correction",
    "df1_read", "df2_read", "p_read", "p_holm", "level_1", "level_2", "mean_diff", "ci95_low", "ci95_high", "dz",
    "dz_ci_low", "dz_ci_high", "note",
]
TWO_LEVEL_COLUMNS = ("mean_diff", "ci95_low", "ci95_high", "dz", "dz_ci_low", "dz_ci_high")


def simple_effects(df: pd.DataFrame, dv: str, within: Sequence[str], subject: str) -> pd.DataFrame:
    """One row per factor and combination of the other factors' levels (``at``: ``kitchen=mid_2``); empty for a
    one-factor design. ``df`` is complete."""
    within = list(within)
    rows: list[pd.DataFrame] = []
    for factor in within if len(within) > 1 else []:
        family = [slice_effect(part, dv, factor, subject, label) for label, part in slices(df, within, factor)]
        rows.append(holm_family(family))
    if not rows:
        return pd.DataFrame(columns=SIMPLE_EFFECT_COLUMNS)
    return pd.concat(rows, ignore_index=True)[SIMPLE_EFFECT_COLUMNS]


def slice_effect(part: pd.DataFrame, dv: str, factor: str, subject: str, label: str) -> pd.DataFrame:
    """The one-way repeated-measures test of ``factor`` on the rows ``part`` (one row, ``at`` = ``label``), with the
    mean difference, its CI and d_z when the factor has two levels."""
    row = rm_anova(part, dv, [factor], subject).iloc[[0]].copy()
    row.insert(0, "factor", factor)
    row.insert(1, "at", label)
    levels = factor_levels(part, factor)
    if len(levels) == 2:
        wide = part.pivot_table(index=subject, columns=factor, values=dv, observed=True)[levels]
        diff = paired_difference(wide[levels[0]].to_numpy(float), wide[levels[1]].to_numpy(float))
        row = row.assign(level_1=levels[0], level_2=levels[1], **{c: diff[c] for c in TWO_LEVEL_COLUMNS})
    return row


def holm_family(family: list[pd.DataFrame]) -> pd.DataFrame:
    """The rows of one family of simple effects with their Holm-adjusted p."""
    block = pd.concat(family, ignore_index=True).reindex(columns=SIMPLE_EFFECT_COLUMNS)
    block["p_holm"] = holm(block["p_read"])
    return block


def holm(pvalues: pd.Series) -> pd.Series:
    """Holm (1979) step-down adjustment, ``p_(i) → max_{j ≤ i} min(1, (m − j + 1) p_(j))``; NaN p values (tests
    that could not be computed) are left out of m and stay NaN."""
    import pingouin as pg

    _, adjusted = pg.multicomp(pvalues.to_numpy(dtype=float), method="holm")
    return pd.Series(adjusted, index=pvalues.index, name="p_holm")
