"""Repeated-measures ANOVA with sphericity (analysis.statistics.anova, analysis.statistics.sphericity) against published
outputs."""

from __future__ import annotations

import itertools

import numpy as np
import pandas as pd
import pingouin as pg
import pytest
from statsmodels.stats.anova import AnovaRM
from steakhouse_published import REACTTIME, agrees, reacttime_long

from analysis.preparation.levels import apply_level_order
from analysis.statistics.anova import ANOVA_COLUMNS, anova_table, ges_bootstrap, rm_anova


def effect(table: pd.DataFrame, name: str) -> pd.Series:
    return table.set_index("effect").loc[name]


def check(actual: float, printed: str) -> None:
    assert agrees(actual, printed), f"{actual!r} does not print as {printed}"


def test_maxwell_delaney_two_way_matches_r() -> None:
    # R's ?anova.mlm and ?mauchly.test on Maxwell & Delaney's Table 12.1 (R sources,
    # tests/Examples/stats-Ex.Rout.save): deg "M = ~deg + noise, X = ~noise", the interaction "X = ~deg + noise",
    # noise "M = ~deg + noise, X = ~deg".
    aov = apply_level_order(reacttime_long(), ["noise", "deg"])
    table = rm_anova(aov, "rt", ["noise", "deg"], "subject")
    assert list(table.columns) == ANOVA_COLUMNS
    assert table["effect"].tolist() == ["noise", "deg", "noise * deg"]
    noise, deg, both = (effect(table, e) for e in ("noise", "deg", "noise * deg"))
    check(noise["F"], "33.766")
    check(noise["p"], "0.00025597")
    assert (noise["df1"], noise["df2"], noise["correction"]) == (1, 9, "none")
    check(deg["F"], "40.719")
    check(deg["p"], "2.0868e-07")
    assert (deg["df1"], deg["df2"]) == (2, 18)
    check(deg["eps_gg"], "0.9616")
    check(deg["eps_hf"], "1.2176")
    check(deg["p_gg"], "3.4017e-07")
    check(deg["p_hf"], "2.0868e-07")  # ε_HF > 1 is used as 1: the uncorrected p
    check(deg["mauchly_W"], "0.9601")
    check(deg["mauchly_p"], "0.8497")
    check(both["F"], "45.31")
    check(both["p"], "9.4241e-08")
    check(both["eps_gg"], "0.904")
    check(both["eps_hf"], "1.118")
    check(both["p_gg"], "3.4539e-07")
    check(both["mauchly_W"], "0.8938")
    check(both["mauchly_p"], "0.6381")
    assert deg["correction"] == both["correction"] == "HF"
    assert (deg["df1_read"], deg["df2_read"], deg["p_read"]) == (2, 18, deg["p"])


def test_maxwell_delaney_six_conditions_one_way_matches_r() -> None:
    # R's "anova(mlmfit, mlmfit0, X = ~1, test = 'Spherical')" and "mauchly.test(mlmfit, X = ~1)": one factor of
    # six levels, where Mauchly's p needs the second-order term (d = 5).
    table = anova_table(REACTTIME, [6], ["condition"])
    row = table.iloc[0]
    check(row["F"], "38.028")
    check(row["p"], "4.4711e-15")
    check(row["eps_gg"], "0.4855")
    check(row["eps_hf"], "0.6778")
    check(row["p_gg"], "2.532e-08")
    check(row["p_hf"], "7.393e-11")
    check(row["mauchly_W"], "0.0311")
    check(row["mauchly_p"], "0.04765")
    assert row["correction"] == "GG" and row["mauchly_df"] == 14
    assert row["df1_read"] == pytest.approx(5 * row["eps_gg"]) and row["p_read"] == row["p_gg"]


def test_rm_anova2_sphericity_matches_ez() -> None:
    # R's ez::ezANOVA on pingouin's rm_anova2 data, as recorded in pingouin's tests/test_distribution.py: GG ε of
    # Metric .9691030 (HF 1), of Time × Metric .7271664 (HF .831161); Mauchly W .968, p .8784418 (Metric) and
    # W .625, p .1523917 (interaction).
    table = rm_anova(pg.read_dataset("rm_anova2"), "Performance", ["Time", "Metric"], "Subject")
    metric, both = effect(table, "Metric"), effect(table, "Time * Metric")
    assert [metric["eps_gg"], min(metric["eps_hf"], 1)] == pytest.approx([0.9691030, 1.0], rel=1e-6)
    assert [both["eps_gg"], both["eps_hf"]] == pytest.approx([0.7271664, 0.831161], rel=1e-6)
    check(metric["mauchly_W"], "0.968")
    check(both["mauchly_W"], "0.625")
    assert [metric["mauchly_p"], both["mauchly_p"]] == pytest.approx([0.8784418, 0.1523917], rel=1e-6)


def test_two_way_matches_jamovi_reference() -> None:
    # JAMOVI values for rm_anova2 as recorded in pingouin's tests/test_parametric.py::test_rm_anova2.
    table = rm_anova(pg.read_dataset("rm_anova2"), "Performance", ["Time", "Metric"], "Subject")
    assert table["df2"].tolist() == [9, 18, 18]
    assert table["F"].to_numpy() == pytest.approx([33.85228, 26.95919, 12.63227], rel=1e-4)
    assert table["MS"].to_numpy() == pytest.approx([828.81667, 682.61667, 112.21667], rel=1e-4)
    assert table["ges"].to_numpy() == pytest.approx([0.25401, 0.35933, 0.08442], rel=1e-4)
    assert table["partial_eta2"].to_numpy() == pytest.approx([0.78998, 0.74972, 0.58395], rel=1e-4)
    assert (table["MSE"] * table["df2"]).to_numpy() == pytest.approx(table["SS_error"].to_numpy())


def test_one_and_two_way_agree_with_pingouin() -> None:
    one = pg.read_dataset("rm_anova_wide").dropna()
    long = one.reset_index().melt(id_vars="index", var_name="time", value_name="score")
    ours = rm_anova(apply_level_order(long, ["time"]), "score", ["time"], "index").iloc[0]
    theirs = pg.rm_anova(data=long, dv="score", within="time", subject="index", correction=True, detailed=True)
    assert ours["F"] == pytest.approx(theirs.at[0, "F"], rel=1e-10)
    assert ours["p_gg"] == pytest.approx(theirs.at[0, "p_GG_corr"], rel=1e-10)
    assert ours["mauchly_W"] == pytest.approx(theirs.at[0, "W_spher"], rel=1e-10)
    assert ours["ges"] == pytest.approx(theirs.at[0, "ng2"], rel=1e-10)
    two = pg.read_dataset("rm_anova2")
    ours2 = rm_anova(two, "Performance", ["Time", "Metric"], "Subject")
    theirs2 = pg.rm_anova(data=two, dv="Performance", within=["Time", "Metric"], subject="Subject")
    assert ours2["eps_gg"].to_numpy() == pytest.approx(theirs2["eps"].to_numpy(), rel=1e-10)
    assert ours2["p_gg"].to_numpy() == pytest.approx(theirs2["p_GG_corr"].to_numpy(), rel=1e-10)


def three_way(n: int = 8, seed: int = 3) -> pd.DataFrame:
    rng = np.random.default_rng(seed)
    rows = []
    for s in range(n):
        person = rng.normal(0, 3)
        for (a, b, c) in itertools.product(range(2), range(2), range(3)):
            y = person + 2 * a - b + 0.8 * c * a + rng.normal(0, 1 + 0.7 * c)
            rows.append({"s": s, "robot": f"a{a}", "kitchen": f"b{b}", "view": f"c{c}", "y": y})
    return pd.DataFrame(rows)


def test_three_factors_agree_with_statsmodels_and_add_up() -> None:
    df = three_way()
    ours = rm_anova(df, "y", ["robot", "kitchen", "view"], "s")
    assert ours["effect"].tolist() == ["robot", "kitchen", "view", "robot * kitchen", "robot * view",
                                       "kitchen * view", "robot * kitchen * view"]
    ref = AnovaRM(df, "y", "s", within=["robot", "kitchen", "view"]).fit().anova_table
    assert ours["F"].to_numpy() == pytest.approx(ref["F Value"].to_numpy(), rel=1e-9)
    assert ours["p"].to_numpy() == pytest.approx(ref["Pr > F"].to_numpy(), rel=1e-9)
    assert ours["df2"].tolist() == ref["Den DF"].astype(int).tolist()
    subjects = df.groupby("s")["y"].mean()
    ss_subjects = 12 * ((subjects - df["y"].mean()) ** 2).sum()
    total = ((df["y"] - df["y"].mean()) ** 2).sum()
    assert ours["SS"].sum() + ours["SS_error"].sum() + ss_subjects == pytest.approx(total)
    errors = ss_subjects + ours["SS_error"].sum()
    assert ours["ges"].to_numpy() == pytest.approx((ours["SS"] / (ours["SS"] + errors)).to_numpy())


def test_three_way_interaction_sphericity_is_the_one_way_sphericity_of_its_contrast() -> None:
    # With robot and kitchen at two levels, the three-way contrast scores are the double differences
    # y11v − y12v − y21v + y22v (up to a constant): their sphericity across view is pingouin's one-way test.
    df = three_way()
    ours = effect(rm_anova(df, "y", ["robot", "kitchen", "view"], "s"), "robot * kitchen * view")
    wide = df.pivot_table(index="s", columns=["robot", "kitchen", "view"], values="y")
    double = pd.DataFrame({c: wide[("a0", "b0", c)] - wide[("a0", "b1", c)] - wide[("a1", "b0", c)]
                           + wide[("a1", "b1", c)] for c in ("c0", "c1", "c2")})
    assert ours["eps_gg"] == pytest.approx(pg.epsilon(double), rel=1e-10)
    assert ours["eps_hf"] == pytest.approx(pg.epsilon(double, correction="hf"), rel=1e-10)
    assert ours["mauchly_W"] == pytest.approx(pg.sphericity(double)[1], rel=1e-10)


def test_an_effect_that_cannot_be_tested_says_why_and_the_others_still_run() -> None:
    df = pg.read_dataset("rm_anova2")
    df["Performance"] = df["Performance"].astype(float)
    df.loc[df["Time"] == "Post", "Performance"] = df.loc[df["Time"] == "Pre", "Performance"].to_numpy() + 5.0
    table = rm_anova(df, "Performance", ["Time", "Metric"], "Subject")
    time, metric, both = (effect(table, e) for e in ("Time", "Metric", "Time * Metric"))
    assert np.isnan(time["F"]) and time["note"].startswith("not testable: no error variance")
    assert np.isnan(both["F"]) and both["note"] == "not testable: no variance in this effect"
    assert np.isfinite(metric["F"]) and metric["note"] == ""
    constant = df.assign(Performance=3.0)
    assert set(rm_anova(constant, "Performance", ["Time", "Metric"], "Subject")["note"]) == {
        "not testable: no variance (every value is the same)"}


def test_partial_eta_interval_and_ges_bootstrap() -> None:
    table = anova_table(REACTTIME, [2, 3], ["noise", "deg"])
    for _, row in table.iterrows():
        assert row["partial_eta2_ci_low"] < row["partial_eta2"] < row["partial_eta2_ci_high"]
    first = ges_bootstrap(REACTTIME, [2, 3], ["noise", "deg"], np.random.default_rng(7), resamples=400)
    again = ges_bootstrap(REACTTIME, [2, 3], ["noise", "deg"], np.random.default_rng(7), resamples=400)
    assert first == again
    for (low, high), ges in zip(first, table["ges"], strict=True):
        assert 0 <= low < ges < high <= 1
