"""Two-way RM-ANOVA and simple main effects against published reference values."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pingouin as pg
import pytest
from scipy import stats
from statsmodels.stats.anova import AnovaRM
from statsmodels.stats.multitest import multipletests

from analysis.anova import ANOVA_COLUMNS, SIMPLE_EFFECT_COLUMNS, holm, rm_anova_2way
from analysis.anova import simple_main_effects
from analysis.errors import AnalysisInputError


def assert_sig(actual: pd.Series, expected: list[float]) -> None:
    """Agreement to 4 significant digits: relative difference below 1e-4.

    (Rounding both sides to 4 digits would fail on ties such as 0.583955 vs the published 0.58395.)
    """
    assert actual.to_numpy(dtype=float) == pytest.approx(expected, rel=1e-4)


@pytest.fixture
def rm2() -> pd.DataFrame:
    """pingouin's bundled 2 (Time) × 3 (Metric) within design, 10 subjects."""
    return pg.read_dataset("rm_anova2")


def test_two_way_matches_jamovi_reference(rm2: pd.DataFrame) -> None:
    # Reference: pingouin's tests/test_parametric.py::test_rm_anova2, values checked there against
    # JAMOVI for read_dataset("rm_anova2"): F, MS, ng2 (generalized η²) and np2 (partial η²).
    aov = rm_anova_2way(rm2, "Performance", ["Time", "Metric"], "Subject")
    assert list(aov.columns) == ANOVA_COLUMNS
    assert aov["effect"].tolist() == ["Time", "Metric", "Time * Metric"]
    assert aov["df1"].tolist() == [1, 2, 2]
    assert aov["df2"].tolist() == [9, 18, 18]
    assert_sig(aov["F"], [33.85228, 26.95919, 12.63227])
    assert_sig(aov["MS"], [828.81667, 682.61667, 112.21667])
    assert_sig(aov["ges"], [0.25401, 0.35933, 0.08442])
    assert_sig(aov["partial_eta2"], [0.78998, 0.74972, 0.58395])
    # p: upper tail of F(df1, df2) at the JAMOVI F values above (scipy.stats.f.sf, pasted once).
    assert_sig(aov["p"], [2.536077e-4, 3.853838e-6, 3.734769e-4])


def test_two_way_agrees_with_statsmodels_anovarm(cells) -> None:
    df = cells(n_subjects=9, seed=4)
    ours = rm_anova_2way(df, "ticks", ["robot", "kitchen"], "participant")
    ref = AnovaRM(df, "ticks", "participant", within=["robot", "kitchen"]).fit().anova_table
    assert ours["F"].to_numpy() == pytest.approx(ref["F Value"].to_numpy(), rel=1e-9)
    assert ours["p"].to_numpy() == pytest.approx(ref["Pr > F"].to_numpy(), rel=1e-9)
    assert ours["df2"].tolist() == [8, 8, 8]


def test_effect_sizes_follow_bakeman_table_1(cells) -> None:
    """ges = SS_effect / (SS_effect + SS_S + every subject × effect SS), computed from scratch."""
    df = cells(n_subjects=7, seed=2)
    y = df.pivot_table(index="participant", columns=["robot", "kitchen"], values="ticks")
    cube = y.to_numpy().reshape(len(y), 2, 2)  # subject × robot × kitchen
    mu = cube.mean()
    m_s, m_a, m_b = cube.mean((1, 2)), cube.mean((0, 2)), cube.mean((0, 1))
    m_ab, m_as, m_bs = cube.mean(0), cube.mean(2), cube.mean(1)
    n = len(y)
    ss_s = 4 * ((m_s - mu) ** 2).sum()
    ss_a = 2 * n * ((m_a - mu) ** 2).sum()
    ss_b = 2 * n * ((m_b - mu) ** 2).sum()
    ss_ab = n * ((m_ab - m_a[:, None] - m_b[None, :] + mu) ** 2).sum()
    ss_as = 2 * ((m_as - m_s[:, None] - m_a[None, :] + mu) ** 2).sum()
    ss_bs = 2 * ((m_bs - m_s[:, None] - m_b[None, :] + mu) ** 2).sum()
    ss_abs = ((cube - mu) ** 2).sum() - ss_s - ss_a - ss_b - ss_ab - ss_as - ss_bs
    errors = ss_s + ss_as + ss_bs + ss_abs
    effects = np.array([ss_a, ss_b, ss_ab])
    aov = rm_anova_2way(df, "ticks", ["robot", "kitchen"], "participant")
    assert aov["SS"].to_numpy() == pytest.approx(effects)
    assert aov["ges"].to_numpy() == pytest.approx(effects / (effects + errors))
    partial = effects / (effects + np.array([ss_as, ss_bs, ss_abs]))
    assert aov["partial_eta2"].to_numpy() == pytest.approx(partial)


def test_simple_effects_match_jamovi_one_way_reference() -> None:
    # Reference: pingouin's tests/test_parametric.py::test_rm_anova, checked there against JAMOVI:
    # one-way RM-ANOVA of Scores on Time in read_dataset("mixed_anova"): F = 3.91280,
    # p = .02263, η²G = .03998, df (2, 118). The same data under two levels of `copy` must give
    # that result at each level, and Holm over two equal p values doubles both.
    base = pg.read_dataset("mixed_anova")
    df = pd.concat([base.assign(copy="x"), base.assign(copy="y")], ignore_index=True)
    simple = simple_main_effects(df, "Scores", "Time", "copy", "Subject")
    assert list(simple.columns) == SIMPLE_EFFECT_COLUMNS
    assert simple["level"].tolist() == ["x", "y"]
    assert simple["effect"].tolist() == ["Time", "Time"]
    assert simple["df1"].tolist() == [2, 2]
    assert simple["df2"].tolist() == [118, 118]
    assert_sig(simple["F"], [3.91280, 3.91280])
    assert_sig(simple["p"], [0.02263, 0.02263])
    assert_sig(simple["ges"], [0.03998, 0.03998])
    assert simple["p_holm"].to_numpy() == pytest.approx(2 * simple["p"].to_numpy())


def test_two_level_simple_effect_is_the_squared_paired_t(rm2: pd.DataFrame) -> None:
    simple = simple_main_effects(rm2, "Performance", "Time", "Metric", "Subject")
    for _, row in simple.iterrows():
        part = rm2[rm2["Metric"] == row["level"]].pivot(
            index="Subject", columns="Time", values="Performance"
        )
        t = stats.ttest_rel(part["Pre"], part["Post"])
        assert row["F"] == pytest.approx(t.statistic**2)
        assert row["p"] == pytest.approx(t.pvalue)
        assert (row["df1"], row["df2"]) == (1, 9)


def test_holm_matches_statsmodels(rm2: pd.DataFrame) -> None:
    simple = simple_main_effects(rm2, "Performance", "Time", "Metric", "Subject")
    expected = multipletests(simple["p"], method="holm")[1]
    assert simple["p_holm"].to_numpy() == pytest.approx(expected, rel=1e-12)
    assert len(set(np.round(simple["p"], 6))) == 3  # three distinct p: every Holm step is used
    pvalues = pd.Series([0.01, 0.04, 0.03, 0.2, 0.005, 0.04])
    assert holm(pvalues).to_numpy() == pytest.approx(multipletests(pvalues, method="holm")[1])


def test_incomplete_data_is_refused_not_silently_dropped(cells) -> None:
    df = cells().iloc[1:]
    with pytest.raises(AnalysisInputError, match="P01: missing cell robot=baseline"):
        rm_anova_2way(df, "ticks", ["robot", "kitchen"], "participant")
    with pytest.raises(AnalysisInputError, match="complete_cases"):
        simple_main_effects(df, "ticks", "robot", "kitchen", "participant")


def test_needs_exactly_two_factors(cells) -> None:
    with pytest.raises(AnalysisInputError, match="exactly two"):
        rm_anova_2way(cells(), "ticks", ["robot"], "participant")
