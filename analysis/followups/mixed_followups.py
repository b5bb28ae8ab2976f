"""Follow-ups of a mixed design (one factor between participants, :mod:`analysis.statistics.mixed_anova`).

* The between factor at each within cell: a one-way between-participants ANOVA of that cell's values (F on
  (G − 1, N − G) df; η² as its η²G); with two groups also the mean difference and its 95 % CI (Student's t, the
  same test). Holm within the family (the between factor across the cells). The same in both conventions below
  (``emmeans``' joint test of the between factor at a cell is this ANOVA).
* Each within factor within each group (and each combination of the other within factors' levels, ``at``:
  ``view=first_person, kitchen=mid_2``), Holm within the factor's family.
* Pairwise: each within factor with more than two levels within each group (``at`` starting with the group); a
  between factor with more than two levels on the participants' means over all cells (``dz`` empty: the groups
  are not paired).

Two conventions for the error of the within-group tests (``error``):

* ``pooled`` (the default, as ``emmeans`` on an ``afex`` model): the within-group covariance pooled over every
  group, N − G df (:mod:`analysis.followups.pooled_followups`); a between factor's pairs on the variance pooled over
  every group.
* ``per-group``: each group's participants alone, as a separate analysis of each group would: the one-way
  repeated-measures test of :func:`analysis.followups.simple_effects.slice_effect` (n_g − 1 df, sphericity-corrected as
  the omnibus table), paired t tests (:mod:`analysis.followups.pairwise`), and Student's t on the two groups compared.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence

import numpy as np
import pandas as pd
from scipy import stats

from analysis.followups.pairwise import PAIRWISE_COLUMNS, pairwise_comparisons
from analysis.followups.pooled_followups import (
    PooledDesign,
    pooled_design,
    pooled_group_pair,
    pooled_pairs,
    pooled_simple_effect,
)
from analysis.followups.simple_effects import SIMPLE_EFFECT_COLUMNS, holm, holm_family, slice_effect
from analysis.preparation.cells import factor_levels, slices
from analysis.preparation.options import PER_GROUP, POOLED
from analysis.statistics.descriptives import DESCRIPTIVE_STATS, cell_descriptives


def mixed_simple_effects(df: pd.DataFrame, dv: str, within: Sequence[str], between: str, subject: str,
                         error: str = POOLED) -> pd.DataFrame:
    within = list(within)
    _check(error)
    design = pooled_design(df, dv, within, between, subject) if error == POOLED else None
    # slices() over the factors other than the between one: every within cell, in design order
    blocks = [holm_family([between_effect(part, dv, between, label) for label, part in slices(df, within, between)])]
    for factor in within:
        family = []
        for g, group in enumerate(factor_levels(df, between)):
            part = df[df[between] == group]
            here = f"{between}={group}"
            others = [f for f in within if f != factor]
            combos = itertools.product(*(factor_levels(part, f) for f in others))
            pieces = slices(part, within, factor) if len(within) > 1 else iter([("", part)])
            for (label, piece), combo in zip(pieces, combos, strict=True):
                row = slice_effect(piece, dv, factor, subject, ", ".join(filter(None, (here, label))))
                if design is not None:
                    row = _pooled_row(row, design, g, factor, dict(zip(others, combo, strict=True)))
                family.append(row)
        blocks.append(holm_family(family))
    return pd.concat(blocks, ignore_index=True)[SIMPLE_EFFECT_COLUMNS]


def _pooled_row(row: pd.DataFrame, design: PooledDesign, group: int, factor: str, at: dict[str, object]
                ) -> pd.DataFrame:
    """The per-group ``row`` of a simple effect (its η²G, levels and mean difference are the group's) with the test
    on the pooled covariance."""
    tested = pooled_simple_effect(design, group, factor, at)
    out = row.copy()
    for column, value in tested.items():
        out[column] = [value]
    return out


def _check(error: str) -> None:
    if error not in (POOLED, PER_GROUP):
        raise ValueError(f"follow-up error {error!r}: {POOLED} or {PER_GROUP}")


def between_effect(part: pd.DataFrame, dv: str, between: str, label: str) -> pd.DataFrame:
    """The one-way between-participants ANOVA of one cell (one row per participant)."""
    levels = factor_levels(part, between)
    groups = [part.loc[part[between] == g, dv].to_numpy(dtype=float) for g in levels]
    values = np.concatenate(groups)
    n, k = len(values), len(groups)
    ss_b = float(sum(len(g) * (g.mean() - values.mean()) ** 2 for g in groups))
    ss_w = float(sum(((g - g.mean()) ** 2).sum() for g in groups))
    df1, df2 = k - 1, n - k
    note = ""
    if df2 < 1 or any(len(g) < 1 for g in groups):
        note = "not testable: too few participants in a group"
    elif ss_w <= 1e-12 * max(ss_b + ss_w, 1.0):
        note = "not testable: no variance within the groups"
    f = math.nan if note else (ss_b / df1) / (ss_w / df2)
    p = math.nan if note else float(stats.f.sf(f, df1, df2))
    row: dict[str, object] = {
        "factor": between, "at": label, "df1": df1, "df2": df2, "MSE": ss_w / df2 if df2 > 0 else math.nan,
        "F": f, "p": p, "ges": ss_b / (ss_b + ss_w) if ss_b + ss_w > 0 else math.nan, "eps_gg": math.nan,
        "eps_hf": math.nan, "correction": "none", "df1_read": df1, "df2_read": df2, "p_read": p, "note": note}
    if k == 2 and not note:
        _, _, _, low, high = student_t(groups[0], groups[1])
        row.update(level_1=levels[0], level_2=levels[1], mean_diff=float(groups[0].mean() - groups[1].mean()),
                   ci95_low=low, ci95_high=high)
    return pd.DataFrame([row]).reindex(columns=SIMPLE_EFFECT_COLUMNS)


def mixed_pairwise(df: pd.DataFrame, dv: str, within: Sequence[str], between: str, subject: str,
                   error: str = POOLED) -> pd.DataFrame:
    _check(error)
    within = list(within)
    design = pooled_design(df, dv, within, between, subject) if error == POOLED else None
    blocks = []
    for g, group in enumerate(factor_levels(df, between)):
        here = f"{between}={group}"
        if design is None:
            block = pairwise_comparisons(df[df[between] == group], dv, within, subject)
            if not block.empty:
                block["at"] = [", ".join(filter(None, (here, str(at)))) for at in block["at"]]
                blocks.append(block)
            continue
        blocks += _pooled_pairwise(design, g, here, df[df[between] == group])
    levels = factor_levels(df, between)
    if len(levels) > 2:
        means = df.groupby([between, subject], observed=True)[dv].mean()
        rows = [_independent(between, means, a, b, error) for a, b in itertools.combinations(levels, 2)]
        block = pd.DataFrame(rows).reindex(columns=PAIRWISE_COLUMNS)
        block["p_holm"] = holm(block["p"])
        blocks.append(block)
    if not blocks:
        return pd.DataFrame(columns=PAIRWISE_COLUMNS)
    return pd.concat(blocks, ignore_index=True)[PAIRWISE_COLUMNS]


def _pooled_pairwise(design: PooledDesign, group: int, here: str, part: pd.DataFrame) -> list[pd.DataFrame]:
    """The families of :func:`analysis.followups.pairwise.pairwise_comparisons` (marginal means, then each slice) of one
    group, tested on the pooled covariance."""
    blocks = []
    for f, factor in enumerate(design.within):
        if len(design.levels[f]) < 3:
            continue
        others = [o for o in design.within if o != factor]
        families: list[tuple[str, dict[str, object]]] = [("", {})]
        if others:
            combos = itertools.product(*(design.levels[design.within.index(o)] for o in others))
            labels = (label for label, _ in slices(part, list(design.within), factor))
            families += [(label, dict(zip(others, combo, strict=True)))
                         for label, combo in zip(labels, combos, strict=True)]
        for label, at in families:
            block = pd.DataFrame(pooled_pairs(design, group, factor, at))
            block["at"] = ", ".join(filter(None, (here, label)))
            block["p_holm"] = holm(block["p"])
            blocks.append(block)
    return blocks


def _independent(between: str, means: pd.Series, a: object, b: object, error: str) -> dict[str, object]:
    x, y = means.loc[a].to_numpy(dtype=float), means.loc[b].to_numpy(dtype=float)
    if error == POOLED:
        groups = means.index.get_level_values(between)
        codes = np.asarray(pd.Categorical(groups).codes)
        names = list(pd.Categorical(groups).categories)
        t, df, p, low, high = pooled_group_pair(means.to_numpy(dtype=float), codes, names.index(a), names.index(b))
        note = ("independent groups (t on the participants' means over all cells, the variance pooled over every "
                "group)")
    else:
        t, df, p, low, high = student_t(x, y)
        note = "independent groups (Student's t on the participants' means over all cells)"
    if math.isnan(t):
        note += "; not testable: " + ("too few participants" if df < 1 else "no variance within the groups")
    se = math.nan if math.isnan(t) else (high - low) / (2 * float(stats.t.ppf(0.975, df)))
    return {"factor": between, "at": "", "level_1": a, "level_2": b, "n": len(x) + len(y),
            "mean_1": float(x.mean()), "mean_2": float(y.mean()), "mean_diff": float(x.mean() - y.mean()), "se": se,
            "ci95_low": low, "ci95_high": high, "t": t, "df": df, "p": p, "note": note}


def student_t(x: np.ndarray, y: np.ndarray) -> tuple[float, int, float, float, float]:
    """Student's two-sample t with pooled variance: ``(t, df, two-sided p, CI low, CI high)``, the 95 % CI of
    mean(x) − mean(y); NaN (but df) when a group is empty, df < 1 or neither group varies. Computed here rather than
    with scipy's ``ttest_ind``, which warns of precision loss whenever a group's values are all equal (a variance of
    exactly 0: nothing is lost) and so failed a study whose group happened to agree."""
    nx, ny = len(x), len(y)
    df = nx + ny - 2
    nan = math.nan
    if nx < 1 or ny < 1 or df < 1:
        return nan, max(df, 0), nan, nan, nan
    diff = float(x.mean() - y.mean())
    pooled = float(((x - x.mean()) ** 2).sum() + ((y - y.mean()) ** 2).sum()) / df
    se = math.sqrt(pooled * (1 / nx + 1 / ny))
    if not se > 0:
        return nan, df, nan, nan, nan
    t = diff / se
    half = float(stats.t.ppf(0.975, df)) * se
    return t, df, float(2 * stats.t.sf(abs(t), df)), diff - half, diff + half


def mixed_descriptives(df: pd.DataFrame, dv: str, within: Sequence[str], between: str, subject: str
                       ) -> pd.DataFrame:
    """Cell descriptives per group (within-subject CIs computed within each group)."""
    blocks = [cell_descriptives(df[df[between] == g], dv, within, subject).assign(**{between: g})
              for g in factor_levels(df, between)]
    return pd.concat(blocks, ignore_index=True)[[between, *within, *DESCRIPTIVE_STATS]]
