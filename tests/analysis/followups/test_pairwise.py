"""Pairwise paired comparisons (analysis.followups.pairwise) against published values and scipy."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import stats
from statsmodels.stats.multitest import multipletests
from steakhouse_published import JASP_PROPORTIONS, reacttime_long

from analysis.followups.paired import paired_difference
from analysis.followups.pairwise import PAIRWISE_COLUMNS, pairwise_comparisons
from analysis.preparation.levels import apply_level_order


def test_paired_difference_matches_jasp() -> None:
    # JASP (jaspTTests test-ttestonesample.R, jasp-issues #1158): mean difference -0.0338624338624338 with 95% CI
    # [-0.219042855717774, 0.151317987992907], t(17) = -0.385804772181173, p = 0.704426623388777,
    # d = -0.0909350568744795, 95% CI [-0.552576696667502, 0.373348871605267].
    out = paired_difference(JASP_PROPORTIONS, np.full(len(JASP_PROPORTIONS), 0.5))
    assert out["mean_diff"] == pytest.approx(-0.0338624338624338, rel=1e-10)
    assert [out["ci95_low"], out["ci95_high"]] == pytest.approx([-0.219042855717774, 0.151317987992907], rel=1e-9)
    assert [out["t"], out["p"], out["df"]] == pytest.approx([-0.385804772181173, 0.704426623388777, 17], rel=1e-9)
    assert [out["dz"], out["dz_ci_low"], out["dz_ci_high"]] == pytest.approx(
        [-0.0909350568744795, -0.552576696667502, 0.373348871605267], rel=1e-8)


def test_three_levels_in_study_order_with_holm() -> None:
    df = apply_level_order(reacttime_long(), ["noise", "deg"], {"deg": ["8", "4", "0"]})
    table = pairwise_comparisons(df, "rt", ["noise", "deg"], "subject")
    assert list(table.columns) == PAIRWISE_COLUMNS
    assert list(dict.fromkeys(table["at"])) == ["", "noise=absent", "noise=present"]
    table = table[table["at"] == ""]
    assert list(zip(table["level_1"], table["level_2"], strict=True)) == [("8", "4"), ("8", "0"), ("4", "0")]
    means = df.groupby(["subject", "deg"], observed=True)["rt"].mean().unstack()
    for _, row in table.iterrows():
        ref = stats.ttest_rel(means[row["level_1"]], means[row["level_2"]])
        assert row["t"] == pytest.approx(ref.statistic) and row["p"] == pytest.approx(ref.pvalue)
        diff = means[row["level_1"]] - means[row["level_2"]]
        assert row["dz"] == pytest.approx(diff.mean() / diff.std(ddof=1))
        assert row["se"] == pytest.approx(diff.std(ddof=1) / np.sqrt(10))
    assert table["p_holm"].to_numpy() == pytest.approx(multipletests(table["p"], method="holm")[1])


def test_comparisons_within_each_level_of_the_other_factor_are_holm_adjusted_per_level() -> None:
    df = apply_level_order(reacttime_long(), ["noise", "deg"], {"deg": ["8", "4", "0"]})
    table = pairwise_comparisons(df, "rt", ["noise", "deg"], "subject")
    for noise in ("absent", "present"):
        family = table[table["at"] == f"noise={noise}"]
        assert list(zip(family["level_1"], family["level_2"], strict=True)) == [("8", "4"), ("8", "0"), ("4", "0")]
        values = df[df["noise"] == noise].pivot(index="subject", columns="deg", values="rt")
        for _, row in family.iterrows():
            ref = stats.ttest_rel(values[row["level_1"]], values[row["level_2"]])
            ci = ref.confidence_interval(0.95)
            assert [row["t"], row["p"]] == pytest.approx([ref.statistic, ref.pvalue])
            assert [row["ci95_low"], row["ci95_high"]] == pytest.approx([ci.low, ci.high])
            diff = values[row["level_1"]] - values[row["level_2"]]
            assert [row["mean_diff"], row["dz"]] == pytest.approx([diff.mean(), diff.mean() / diff.std(ddof=1)])
        assert family["p_holm"].to_numpy() == pytest.approx(multipletests(family["p"], method="holm")[1])


def test_two_level_factors_have_no_pairwise_rows_and_equal_differences_are_not_testable() -> None:
    df = reacttime_long()
    assert pairwise_comparisons(df[df["deg"] != "8"], "rt", ["noise", "deg"], "subject").empty
    same = paired_difference(np.array([1.0, 2.0, 3.0]), np.array([0.0, 1.0, 2.0]))
    assert same["note"] == "not testable: every participant has the same difference" and np.isnan(same["t"])
