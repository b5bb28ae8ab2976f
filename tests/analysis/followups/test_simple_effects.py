"""Simple main effects in every direction (analysis.followups.simple_effects)."""

from __future__ import annotations

import pandas as pd
import pingouin as pg
import pytest
from statsmodels.stats.multitest import multipletests
from steakhouse_published import reacttime_long

from analysis.followups.simple_effects import SIMPLE_EFFECT_COLUMNS, holm, simple_effects
from analysis.preparation.levels import apply_level_order


def test_both_directions_each_a_one_way_anova_of_its_slice() -> None:
    df = apply_level_order(reacttime_long(), ["noise", "deg"])
    table = simple_effects(df, "rt", ["noise", "deg"], "subject")
    assert list(table.columns) == SIMPLE_EFFECT_COLUMNS
    assert list(zip(table["factor"], table["at"], strict=True)) == [
        ("noise", "deg=0"), ("noise", "deg=4"), ("noise", "deg=8"), ("deg", "noise=absent"), ("deg", "noise=present")]
    for _, row in table.iterrows():
        other, level = row["at"].split("=")
        part = df[df[other] == level]
        ref = pg.rm_anova(data=part, dv="rt", within=row["factor"], subject="subject", correction=True)
        assert row["F"] == pytest.approx(ref.at[0, "F"]) and row["p"] == pytest.approx(ref.at[0, "p_unc"])
        if row["df1"] > 1:
            assert row["eps_gg"] == pytest.approx(ref.at[0, "eps"])
    for _, family in table.groupby("factor"):
        assert family["p_holm"].to_numpy() == pytest.approx(multipletests(family["p_read"], method="holm")[1])


def test_three_factors_give_each_factor_in_each_cell_of_the_others() -> None:
    base = reacttime_long()
    df = pd.concat([base.assign(view=v, rt=base["rt"] + 10 * k) for k, v in enumerate(("top", "first"))])
    table = simple_effects(df, "rt", ["noise", "deg", "view"], "subject")
    assert table.groupby("factor", sort=False).size().to_dict() == {"noise": 6, "deg": 4, "view": 6}
    assert "deg=0, view=top" in set(table["at"])


def test_a_slice_without_variance_is_not_testable_and_holm_skips_it() -> None:
    # A crash once seen: pingouin dropped the F column of a slice where every value is the same.
    df = pg.read_dataset("rm_anova2")
    df.loc[df["Metric"] == "Action", "Performance"] = 0
    table = simple_effects(df, "Performance", ["Time", "Metric"], "Subject")
    action = table[(table["factor"] == "Time") & (table["at"] == "Metric=Action")].iloc[0]
    assert action["note"] == "not testable: no variance (every value is the same)"
    assert pd.isna(action["p_holm"])
    others = table[(table["factor"] == "Time") & (table["at"] != "Metric=Action")]
    assert others["p_holm"].to_numpy() == pytest.approx(multipletests(others["p_read"], method="holm")[1])
    assert holm(pd.Series([0.01, float("nan"), 0.04])).tolist()[0] == pytest.approx(0.02)


def test_a_two_level_simple_effect_gives_its_mean_difference_ci_and_dz() -> None:
    from scipy import stats

    df = apply_level_order(reacttime_long(), ["noise", "deg"])
    table = simple_effects(df, "rt", ["noise", "deg"], "subject")
    for _, row in table[table["factor"] == "noise"].iterrows():
        part = df[df["deg"] == row["at"].split("=")[1]].pivot(index="subject", columns="noise", values="rt")
        assert (row["level_1"], row["level_2"]) == ("absent", "present")
        diff = part["absent"] - part["present"]
        ci = stats.ttest_rel(part["absent"], part["present"]).confidence_interval(0.95)
        assert [row["mean_diff"], row["ci95_low"], row["ci95_high"]] == pytest.approx([diff.mean(), ci.low, ci.high])
        assert row["dz"] == pytest.approx(diff.mean() / diff.std(ddof=1))
        assert row["dz_ci_low"] < row["dz"] < row["dz_ci_high"]
    three = table[table["factor"] == "deg"]
    assert three["mean_diff"].isna().all(), "a three-level simple effect has no single difference"
