"""The simulation power analysis runs the tests ``analyze`` runs, and agrees with the analytic power where one
exists (pingouin's ``power_rm_anova`` for a two-level within effect)."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pandas as pd
import pingouin as pg
import pytest

from analysis.anova import anova_table
from analysis.followups import simple_effects
from analysis.power import MeasureData, measure_power, planned_tests, sample_pvalues, wilson


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
    p = sample_pvalues(values[None], counts, within, tests)[0]
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
    corr = float(np.corrcoef(values.T)[0, 1])
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
