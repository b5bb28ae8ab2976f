"""The simulation power analysis runs the tests ``analyze`` runs, and agrees with the analytic power where one
exists (pingouin's ``power_rm_anova`` for a two-level within effect)."""

from __future__ import annotations

import gc
import itertools
import math

import numpy as np
import pandas as pd
import pingouin as pg
import pytest

from analysis.followups.simple_effects import simple_effects
from analysis.power_analysis.within_power import MeasureData, measure_power, planned_tests, sample_pvalues, wilson
from analysis.statistics.anova import anova_table


def long_table(values: np.ndarray, within: list[str], levels: list[list[str]]) -> pd.DataFrame:
    cells = list(itertools.product(*levels))
    rows = [{"participant": f"p{s}", **dict(zip(within, cell, strict=True)), "y": values[s, c]}
            for s in range(values.shape[0]) for c, cell in enumerate(cells)]
    return pd.DataFrame(rows)


@pytest.mark.parametrize("levels", [[["fov", "base"], ["none_3", "mid_2"]], [["a", "b", "c"], ["k1", "k2"]]])
def test_each_planned_test_gives_the_p_the_analysis_reads(levels) -> None:
    """Omnibus effects: ``anova_table``'s ``p_read`` (sphericity-corrected for a three-level factor); simple
    effects: ``simple_effects``' Holm-adjusted p."""
    rng = np.random.default_rng(4)
    within = ["robot", "kitchen"]
    counts = [len(lv) for lv in levels]
    values = rng.normal(size=(14, math.prod(counts))) + rng.normal(size=(14, 1)) + np.arange(math.prod(counts)) * 0.3
    tests = planned_tests(within, levels)
    p = sample_pvalues(values[None], tests)[0]
    omnibus = anova_table(values, counts, within).set_index("effect")["p_read"]
    simple = simple_effects(long_table(values, within, levels), "y", within, "participant")
    expected = {**omnibus.to_dict(), **{f"{r.factor} at {r.at}": r.p_holm for r in simple.itertuples()}}
    assert [t.name for t in tests] == list(expected)
    assert p == pytest.approx([expected[t.name] for t in tests], rel=1e-9, abs=1e-12)


def test_power_agrees_with_pingouins_analytic_power_for_a_two_level_effect() -> None:
    """A large normal pilot (so the resampled population is close to normal): the simulated power of the
    two-level effect at each n lies within Monte-Carlo error of ``pingouin.power_rm_anova`` given the pilot's
    effect size η² = f² / (1 + f²), f² = ((m₁ − m₂)/2)² / σ², and its correlation between the two conditions."""
    rng = np.random.default_rng(11)
    pilot_n, rho, delta = 600, 0.6, 0.45
    cov = [[1.0, rho], [rho, 1.0]]
    values = rng.multivariate_normal([0.0, delta], cov, size=pilot_n)
    means, sd = values.mean(axis=0), values.std(axis=0)
    sigma2 = float(np.mean(sd ** 2))
    f2 = ((means[1] - means[0]) / 2) ** 2 / sigma2
    corr = float(np.asarray(np.corrcoef(values.T))[0, 1])
    simulations = 4000
    table = measure_power(MeasureData("y", values, ("robot",), (("a", "b"),)), [10, 20, 30], simulations, 0.05,
                          np.random.default_rng(12))
    assert list(table["test"].unique()) == ["robot"]
    for row in table.itertuples():
        analytic = pg.power_rm_anova(eta_squared=f2 / (1 + f2), m=2, n=row.n, corr=corr, alpha=0.05)
        se = math.sqrt(analytic * (1 - analytic) / simulations)
        assert abs(row.power - analytic) < 3.5 * se + 0.01, (row.n, row.power, analytic)


def test_no_effect_gives_power_near_alpha_and_the_interval_holds_it() -> None:
    rng = np.random.default_rng(3)
    values = rng.normal(size=(300, 4)) + rng.normal(size=(300, 1))
    table = measure_power(MeasureData("y", values, ("robot", "kitchen"), (("a", "b"), ("k", "l"))), [16], 2000,
                          0.05, np.random.default_rng(5))
    omnibus = table[table["kind"] == "effect"]
    assert ((omnibus["ci_low"] <= 0.065) & (omnibus["ci_high"] >= 0.035)).all()
    assert len(table) == 3 + 4, "three omnibus effects and four simple effects"


def test_the_wilson_interval_covers_the_estimate() -> None:
    low, high = wilson(80, 100)
    assert low < 0.8 < high and high - low < 0.2
    assert wilson(0, 50)[0] == pytest.approx(0.0, abs=1e-12)


def test_the_vectorised_tests_equal_the_analysis_on_every_resample() -> None:
    """Many resamples of a 3 × 2 pilot, some read with Greenhouse–Geisser, some with Huynh–Feldt, one with no
    variance at all: each p equals ``anova_table``'s ``p_read`` / ``simple_effects``' Holm-adjusted p."""
    rng = np.random.default_rng(8)
    levels = [["a", "b", "c"], ["k1", "k2"]]
    within, counts = ["robot", "kitchen"], [3, 2]
    pilot = rng.normal(size=(10, 6)) * rng.uniform(0.3, 3, size=6) + rng.normal(size=(10, 1)) + np.arange(6) * 0.4
    samples = pilot[rng.integers(10, size=(40, 10))]
    samples[0] = 5.0
    tests = planned_tests(within, levels)
    p = sample_pvalues(samples, tests)
    readings = set()
    for sample, row in zip(samples, p, strict=True):
        table = anova_table(sample, counts, within).set_index("effect")
        readings |= set(table["correction"])
        simple = simple_effects(long_table(sample, within, levels), "y", within, "participant")
        expected = {**table["p_read"].to_dict(), **{f"{r.factor} at {r.at}": r.p_holm for r in simple.itertuples()}}
        assert row == pytest.approx([expected[t.name] for t in tests], rel=1e-9, abs=1e-12, nan_ok=True)
    assert {"GG", "HF"} <= readings, "both corrections were exercised"
    assert np.isnan(p[0]).all(), "a resample without variance is not testable"


def test_the_holm_adjustment_of_every_row_at_once_is_statsmodels() -> None:
    from statsmodels.stats.multitest import multipletests

    from analysis.power_analysis.within_power import holm_matrix

    p = np.random.default_rng(1).uniform(size=(50, 4)) ** 3
    p[3, 1] = np.nan
    adjusted = holm_matrix(p)
    # statsmodels' Holm runs a full gc.collect() on every call, which in a test worker walks every object of the
    # tests run before (0.2-0.9 s a call); frozen, those live objects are left out of the walk.
    gc.freeze()
    try:
        expected = [multipletests(row[~np.isnan(row)], method="holm")[1] for row in p]
    finally:
        gc.unfreeze()
    for row, out, holm in zip(p, adjusted, expected, strict=True):
        ok = ~np.isnan(row)
        assert out[ok] == pytest.approx(holm) and np.isnan(out[~ok]).all()


def test_a_chosen_effect_size_sets_that_effects_generalized_eta_squared_and_nothing_else() -> None:
    from analysis.power_analysis.chosen_effect import EffectSize, with_effect_size

    rng = np.random.default_rng(2)
    values = rng.normal(size=(12, 6)) + rng.normal(size=(12, 1)) + np.array([0, 0.2, 0.5, 0.1, 0.3, 0.9])
    within, counts = ["robot", "kitchen"], [3, 2]
    before = anova_table(values, counts, within).set_index("effect")
    robot = planned_tests(within, [["a", "b", "c"], ["k", "l"]])[0]
    scaled = with_effect_size(values, counts, within, robot.effect, robot.contrast, 0.1)
    assert scaled is not None
    after = anova_table(scaled, counts, within).set_index("effect")
    assert after.loc["robot", "ges"] == pytest.approx(0.1, rel=1e-9)
    assert after["SS_error"].to_numpy() == pytest.approx(before["SS_error"].to_numpy(), rel=1e-9)
    assert after.loc[["kitchen", "robot * kitchen"], "SS"].to_numpy() == pytest.approx(
        before.loc[["kitchen", "robot * kitchen"], "SS"].to_numpy(), rel=1e-9)
    flat = with_effect_size(np.tile(values[:, :1], (1, 6)), counts, within, robot.effect, robot.contrast, 0.1)
    assert flat is None, "no pattern to scale"
    table = measure_power(MeasureData("y", values, tuple(within), (("a", "b", "c"), ("k", "l"))), [8, 40], 400,
                          0.05, np.random.default_rng(3), EffectSize.parse("eta2g=0.1"))
    chosen = table[table["scenario"] == "eta2g=0.1"]
    assert set(chosen["test"]) == {"robot", "kitchen", "robot * kitchen"}
    assert chosen.groupby("test")["power"].apply(lambda s: s.iloc[-1] >= s.iloc[0]).all(), "more n, more power"
    for bad in ("eta2g=1.5", "d=0.3", "eta2g=x"):
        with pytest.raises(Exception, match="--effect"):
            EffectSize.parse(bad)


def test_a_malformed_effect_size_is_a_usage_error(tmp_path, capsys) -> None:
    from server.cli import main

    assert main(["power", "--study", "s", "--n", "8,12", "--out", str(tmp_path), "--effect", "d=0.5"]) == 2
    assert "--effect 'd=0.5': expected eta2g=VALUE" in capsys.readouterr().err
    assert not any(tmp_path.iterdir()), "nothing written"
