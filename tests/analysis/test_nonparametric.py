"""Rank tests for rating measures (analysis.nonparametric) against R's documented outputs and JASP."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from steakhouse_published import DEPRESSION_X, DEPRESSION_Y, JASP_PROPORTIONS, ROUNDING_TIMES, agrees

from analysis.nonparametric import RANK_TEST_COLUMNS, friedman, rank_tests, wilcoxon_signed_rank


def test_friedman_matches_r() -> None:
    # R's ?friedman.test: Friedman chi-squared = 11.1429, df = 2, p-value = 0.003805.
    out = friedman(pd.DataFrame(ROUNDING_TIMES, columns=["round out", "narrow angle", "wide angle"]))
    assert agrees(out["statistic"], "11.1429") and out["df"] == 2 and agrees(out["p"], "0.003805")


def test_wilcoxon_matches_r_and_jasp() -> None:
    # R's ?wilcox.test: V = 40, p-value = 0.01953 one-sided (exact, 9 pairs: 10/512), so 20/512 two-sided.
    out = wilcoxon_signed_rank(DEPRESSION_X, DEPRESSION_Y)
    assert out["statistic"] == 40 and agrees(out["p"] / 2, "0.01953") and out["p"] == pytest.approx(20 / 512)
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
    assert same["note"].startswith("not testable") and np.isnan(same["p"])
    flat = friedman(pd.DataFrame(np.full((4, 3), 2.0)))
    assert flat["note"].startswith("not testable") and np.isnan(flat["statistic"])
