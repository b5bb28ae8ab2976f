"""The mixed design's conventions, each against the package it follows (docs/analysis.md, "Mixed designs: the
conventions"), to 4 significant digits:

* type III sums of squares (the default) and type II against R's ``afex`` (``aov_car``, ``type = 3`` / ``2``), and
  type II against ``pingouin``'s ``mixed_anova`` (run here) on an unbalanced set;
* the pooled follow-ups (the default) against ``emmeans`` on the ``afex`` model (``pairs``, ``joint_tests``);
* the per-group follow-ups against each group analysed alone (``pingouin``'s ``rm_anova``, scipy's paired t).

The R values are in ``tests/analysis/reference/afex_emmeans.csv``, written by ``afex_emmeans.R`` beside it (its
header says how to run it and which versions wrote it). Datasets: pingouin's ``mixed_anova`` (balanced, and
unbalanced without eight Meditation subjects) and O'Brien & Kaiser's (1985) repeated measures with three unequal
treatment groups (``steakhouse_published.OBRIEN_KAISER``).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pandas as pd
import pingouin as pg
import pytest
from scipy import stats
from steakhouse_published import obrien_kaiser_long, to_digits

from analysis.followups.mixed_followups import mixed_pairwise, mixed_simple_effects
from analysis.preparation.cells import factor_levels, group_index, wide_matrix
from analysis.preparation.levels import apply_level_order
from analysis.statistics.mixed_anova import mixed_anova_table

REFERENCE = pd.read_csv(Path(__file__).parents[1] / "reference" / "afex_emmeans.csv", comment="#",
                        keep_default_na=False, dtype={"value": float})


def pingouin_mixed() -> pd.DataFrame:
    return pg.read_dataset("mixed_anova")


def pingouin_unbalanced() -> pd.DataFrame:
    df = pg.read_dataset("mixed_anova")
    return df[~((df["Group"] == "Meditation") & df["Subject"].between(30, 37))].reset_index(drop=True)


Design = tuple[Callable[[], pd.DataFrame], str, list[str], str, str]
DATASETS: dict[str, Design] = {
    "pingouin_mixed": (pingouin_mixed, "Scores", ["Time"], "Group", "Subject"),
    "pingouin_unbalanced": (pingouin_unbalanced, "Scores", ["Time"], "Group", "Subject"),
    "obrien_kaiser": (obrien_kaiser_long, "value", ["phase", "hour"], "treatment", "id"),
}
LEVELS = {"Time": ("August", "January", "June"), "Group": ("Control", "Meditation"),
          "phase": ("pre", "post", "fup"), "hour": ("1", "2", "3", "4", "5"), "treatment": ("control", "A", "B")}


def prepared(name: str) -> tuple[pd.DataFrame, str, list[str], str, str]:
    load, dv, within, between, subject = DATASETS[name]
    return apply_level_order(load(), [*within, between], LEVELS, strict=True), dv, within, between, subject


def reference(dataset: str, package: str) -> pd.DataFrame:
    return REFERENCE[(REFERENCE["dataset"] == dataset) & (REFERENCE["package"] == package)]


def effect(term: str) -> str:
    """afex's ``treatment:phase`` is this project's ``treatment * phase``."""
    return term.replace(":", " * ")


def compare(rows: pd.DataFrame, ours: Callable[[pd.Series], float]) -> int:
    """Every reference row against ``ours(row)`` to 4 significant digits (emmeans' joint-test F to the 3 decimals
    emmeans rounds it to); the number of values compared."""
    for _, row in rows.iterrows():
        value = ours(row)
        if row["package"] == "emmeans" and row["statistic"] == "F":
            assert round(value, 3) == pytest.approx(row["value"], abs=1e-9), (dict(row), value)
        else:
            assert to_digits(value, row["value"]), (dict(row), value)
    return len(rows)


@pytest.mark.parametrize("dataset", list(DATASETS))
@pytest.mark.parametrize("ss_type", [3, 2])
def test_the_mixed_anova_is_afexs_of_either_type(dataset: str, ss_type: int) -> None:
    df, dv, within, between, subject = prepared(dataset)
    values, subjects = wide_matrix(df, dv, within, subject)
    groups = group_index(df, subjects, between, subject, factor_levels(df, between))
    counts = [len(factor_levels(df, f)) for f in within]
    table = mixed_anova_table(values, groups, len(LEVELS[between]), counts, within, between,
                              ss_type=ss_type).set_index("effect")
    columns = {"F": "F", "p": "p", "ges": "ges", "MSE": "MSE", "eps_gg": "eps_gg", "eps_hf": "eps_hf",
               "p_gg": "p_gg", "p_hf": "p_hf"}
    rows = reference(dataset, "afex")
    rows = rows[rows["statistic"].str.endswith(f"_type{ss_type}")]
    compared = compare(rows, lambda r: float(table.loc[effect(r["term"]),
                                                       columns[r["statistic"].rsplit("_type", 1)[0]]]))
    assert compared == {"obrien_kaiser": 7 * 4 + 6 * 4}.get(dataset, 3 * 4 + 2 * 4)


def test_type_ii_is_pingouins_mixed_anova_on_unequal_groups() -> None:
    df, dv, within, between, subject = prepared("pingouin_unbalanced")
    values, subjects = wide_matrix(df, dv, within, subject)
    groups = group_index(df, subjects, between, subject, list(LEVELS[between]))
    ours = mixed_anova_table(values, groups, 2, [3], within, between, ss_type=2)
    theirs = pg.mixed_anova(data=df.astype({"Time": str, "Group": str}), dv=dv, between=between, within="Time",
                            subject=subject, effsize="ng2")
    for mine, (_, row) in zip(ours.itertuples(), theirs.iterrows(), strict=True):
        for value, published in ((mine.SS, row["SS"]), (mine.F, row["F"]), (mine.p, row["p_unc"]),
                                 (mine.ges, row["ng2"])):
            assert to_digits(value, float(published)), (mine.effect, value, published)
    type_iii = mixed_anova_table(values, groups, 2, [3], within, between, ss_type=3).set_index("effect")
    assert not to_digits(type_iii.loc["Time", "F"], float(theirs.loc[1, "F"])), "unequal groups: the types differ"


def emmeans_key(row: pd.Series, between: str) -> tuple[str, str, str, str]:
    """``(factor, at, level_1, level_2)`` of an emmeans pair (``by`` is this project's ``at``)."""
    first, second = (part.strip() for part in str(row["contrast"]).split(" - "))
    return str(row["term"]), str(row["by"]), first, second


PAIR_COLUMNS = {"estimate": "mean_diff", "SE": "se", "df": "df", "t": "t", "p": "p", "lower.CL": "ci95_low",
                "upper.CL": "ci95_high", "p_holm": "p_holm"}


@pytest.mark.parametrize("dataset", list(DATASETS))
def test_the_pooled_follow_ups_are_emmeans_on_the_afex_model(dataset: str) -> None:
    df, dv, within, between, subject = prepared(dataset)
    simple = mixed_simple_effects(df, dv, within, between, subject).set_index(["factor", "at"])
    pairs = mixed_pairwise(df, dv, within, between, subject).set_index(["factor", "at", "level_1", "level_2"])
    rows = reference(dataset, "emmeans")
    joint = rows[rows["contrast"] == ""]
    columns = {"F": "F", "p": "p", "df2": "df2"}
    compared = compare(joint, lambda r: float(simple.loc[(r["term"], r["by"]), columns[r["statistic"]]]))
    paired = rows[rows["contrast"] != ""]
    compared += compare(paired, lambda r: float(pairs.loc[emmeans_key(r, between), PAIR_COLUMNS[r["statistic"]]]))
    assert compared == len(rows) > 0
    two_level = simple[simple["level_1"].notna()]
    for (factor, at), row in two_level.iterrows():  # a two-level simple effect is its pair's t squared
        assert row["F"] == pytest.approx(row["mean_diff"] ** 2 / (row["ci95_high"] - row["mean_diff"]) ** 2
                                         * stats.t.ppf(0.975, row["df2"]) ** 2, rel=1e-9), (factor, at)


def test_the_pooled_d_z_and_its_interval_use_the_pooled_sd() -> None:
    df, dv, within, between, subject = prepared("pingouin_mixed")
    pairs = mixed_pairwise(df, dv, within, between, subject).set_index(["at", "level_1", "level_2"])
    row = pairs.loc[("Group=Meditation", "August", "January")]
    sd = row["se"] * math.sqrt(row["n"])
    assert row["dz"] == pytest.approx(row["mean_diff"] / sd, rel=1e-12)
    # the interval holds the d_z of the noncentral t on N − G df at its bounds
    for bound, tail in ((row["dz_ci_low"], 0.975), (row["dz_ci_high"], 0.025)):
        assert stats.nct.cdf(row["t"], 58, bound * math.sqrt(row["n"])) == pytest.approx(tail, abs=1e-8)


@pytest.mark.parametrize("dataset", ["pingouin_unbalanced", "obrien_kaiser"])
def test_the_per_group_follow_ups_are_each_group_analysed_alone(dataset: str) -> None:
    df, dv, within, between, subject = prepared(dataset)
    simple = mixed_simple_effects(df, dv, within, between, subject, "per-group").set_index(["factor", "at"])
    pairs = mixed_pairwise(df, dv, within, between, subject, "per-group").set_index(
        ["factor", "at", "level_1", "level_2"])
    compared = 0
    for group in LEVELS[between]:
        mine = df[df[between] == group].astype(dict.fromkeys(within, str))
        for factor in within:
            others = [f for f in within if f != factor]
            slices = mine.groupby(others) if others else [((), mine)]
            for key, part in slices:
                at = ", ".join([f"{between}={group}", *(f"{o}={v}" for o, v in zip(others, np.atleast_1d(key),
                                                                                       strict=True))])
                rm = pg.rm_anova(data=part, dv=dv, within=factor, subject=subject)
                assert to_digits(simple.loc[(factor, at), "F"], float(rm.at[0, "F"]))
                assert to_digits(simple.loc[(factor, at), "p"], float(rm.at[0, "p_unc"]))
                assert simple.loc[(factor, at), "df2"] == rm.at[0, "ddof2"]
                compared += 2
                wide = part.pivot(index=subject, columns=factor, values=dv)
                levels = LEVELS[factor]
                for i, a in enumerate(levels):
                    for b in levels[i + 1:]:
                        if len(levels) < 3:
                            continue
                        with warnings.catch_warnings():  # scipy warns when every difference is the same
                            warnings.simplefilter("ignore", RuntimeWarning)
                            test = stats.ttest_rel(wide[a], wide[b])
                        row = pairs.loc[(factor, at, a, b)]
                        assert row["df"] == len(wide) - 1
                        if not math.isfinite(test.statistic):
                            assert row["note"] == "not testable: every participant has the same difference"
                            continue
                        assert to_digits(row["t"], float(test.statistic)) and to_digits(row["p"], float(test.pvalue))
                        compared += 2
    assert compared > 0
