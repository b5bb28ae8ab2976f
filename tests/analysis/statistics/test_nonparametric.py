"""Rank tests for rating measures (analysis.statistics.nonparametric) against R's documented outputs and JASP."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from scipy import stats
from steakhouse_published import DEPRESSION_X, DEPRESSION_Y, JASP_PROPORTIONS, ROUNDING_TIMES, agrees

from analysis.statistics.nonparametric import RANK_TEST_COLUMNS, friedman, rank_tests, wilcoxon_signed_rank


def test_friedman_matches_r() -> None:
    # R's ?friedman.test: Friedman chi-squared = 11.1429, df = 2, p-value = 0.003805.
    out = friedman(pd.DataFrame(ROUNDING_TIMES, columns=["round out", "narrow angle", "wide angle"]))
    assert agrees(out["statistic"], "11.1429") and out["df"] == 2 and agrees(out["p"], "0.003805")


def test_wilcoxon_matches_r_and_jasp() -> None:
    # R's ?wilcox.test: V = 40, p-value = 0.01953 one-sided (exact, 9 pairs: 10/512), so 20/512 two-sided.
    out = wilcoxon_signed_rank(DEPRESSION_X, DEPRESSION_Y)
    p = out["p"]
    assert isinstance(p, float)
    assert out["statistic"] == 40 and agrees(p / 2, "0.01953") and p == pytest.approx(20 / 512)
    # JASP (jaspTTests test-ttestonesample.R): W = 61, p = 0.73267192272089 with zeros and ties (normal
    # approximation with continuity correction, as R's wilcox.test).
    jasp = wilcoxon_signed_rank(JASP_PROPORTIONS, np.full(len(JASP_PROPORTIONS), 0.5))
    assert jasp["statistic"] == 61 and jasp["p"] == pytest.approx(0.73267192272089, rel=1e-9)


def test_one_row_per_factor_and_one_for_all_conditions() -> None:
    rows = []
    for s, (x, y) in enumerate(zip(DEPRESSION_X, DEPRESSION_Y, strict=True)):
        for visit, value in (("first", x), ("second", y)):
            for room in ("a", "b"):
                rows.append({"s": s, "visit": visit, "room": room, "y": value + (0.1 if room == "b" else 0.0)})
    table = rank_tests(pd.DataFrame(rows), "y", ["visit", "room"], "s")
    assert list(table.columns) == RANK_TEST_COLUMNS
    assert table["factor"].tolist() == ["visit", "room", "all conditions"]
    assert table["test"].tolist() == ["Wilcoxon signed-rank", "Wilcoxon signed-rank", "Friedman"]
    assert table.loc[0, "statistic"] == 40


def test_no_difference_is_not_testable() -> None:
    same = wilcoxon_signed_rank(np.ones(5), np.ones(5))
    assert isinstance(same["note"], str) and isinstance(same["p"], float)
    assert same["note"].startswith("not testable") and np.isnan(same["p"])
    flat = friedman(pd.DataFrame(np.full((4, 3), 2.0)))
    assert isinstance(flat["note"], str) and isinstance(flat["statistic"], float)
    assert flat["note"].startswith("not testable") and np.isnan(flat["statistic"])


def test_rank_tests_rank_the_item_sums_not_floating_point_noise() -> None:
    # A scale of three 1-7 items per cell, robot (3 levels) × kitchen (2): a participant's marginal mean is a
    # multiple of 1/6, and summing the same answers in another order gives 4.833333333333334 against
    # 4.833333333333333. Ranked as floats, those are different values and the ties break.
    rng = np.random.default_rng(0)
    rows = []
    for s in range(16):
        for robot in ("fov", "base", "stay"):
            for kitchen in ("a", "b"):
                items = rng.integers(3, 8, size=3)
                rows.append({"s": s, "robot": robot, "kitchen": kitchen, "y": items.sum() / 3,
                             "sum": int(items.sum())})
    df = pd.DataFrame(rows)
    levels = ["fov", "base", "stay"]
    float_means = df.groupby(["s", "robot"])["y"].mean().unstack()[levels].to_numpy()
    sums = df.groupby(["s", "robot"])["sum"].sum().unstack()[levels].to_numpy()
    exact = stats.friedmanchisquare(*sums.T)
    noisy = stats.friedmanchisquare(*float_means.T)
    assert noisy.statistic != pytest.approx(exact.statistic), "the float means do break ties (the test bites)"
    table = rank_tests(df, "y", ["robot", "kitchen"], "s", resolution=1 / 3).set_index("factor")
    assert table.loc["robot", "statistic"] == pytest.approx(exact.statistic, rel=1e-12)
    assert table.loc["robot", "p"] == pytest.approx(exact.pvalue, rel=1e-12)
    # Wilcoxon (kitchen): the signed ranks of the differences of the item sums, as R's wilcox.test ranks them
    k_sums = df.groupby(["s", "kitchen"])["sum"].sum().unstack()[["a", "b"]].to_numpy()
    diff = k_sums[:, 0] - k_sums[:, 1]
    nonzero = diff[diff != 0]
    expected_v = stats.rankdata(np.abs(nonzero))[nonzero > 0].sum()
    assert table.loc["kitchen", "statistic"] == expected_v
    assert table.loc["kitchen", "p"] == pytest.approx(stats.wilcoxon(k_sums[:, 0], k_sums[:, 1], correction=True,
                                                                     method="approx").pvalue, rel=1e-9)
    assert table.loc["all conditions", "levels"].startswith("robot=fov, kitchen=a vs robot=fov, kitchen=b vs "
                                                            "robot=base"), "conditions in study order"


def test_the_resolution_of_a_rating_measure_is_found_in_its_values() -> None:
    from analysis.preparation.measure_info import resolution

    assert resolution(pd.Series([1.0, 4.0, 7.0])) == 1.0
    assert resolution(pd.Series([1.0, 4 + 1 / 3, 17 / 3])) == pytest.approx(1 / 3)
    assert resolution(pd.Series([2.5, 1.0])) == 0.5
    assert resolution(pd.Series([0.123456])) is None
