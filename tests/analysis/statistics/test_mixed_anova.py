"""The mixed (split-plot) ANOVA (analysis.statistics.mixed_anova): pingouin's documented example to 4 significant
digits, and the textbook split-plot sums of squares (marginal means, inclusion–exclusion) for a 3-group × 3 × 2
design."""

from __future__ import annotations

import itertools

import numpy as np
import pandas as pd
import pingouin as pg
import pytest
from split_plot import textbook
from steakhouse_published import agrees

from analysis.statistics.mixed_anova import mixed_anova_table


def wide_of(df: pd.DataFrame, dv: str, between: str, within: list[str], subject: str):
    levels = [list(pd.unique(df[f])) for f in within]
    groups = list(pd.unique(df[between]))
    cells = list(itertools.product(*levels))
    table = df.set_index([subject, *within])[dv]
    subjects = list(pd.unique(df[subject]))
    values = np.array([[table.loc[(s, *c)] for c in cells] for s in subjects], dtype=float)
    group_of = df.drop_duplicates(subject).set_index(subject)[between]
    return values, [groups.index(group_of[s]) for s in subjects], len(groups), [len(lv) for lv in levels]


def test_pingouins_documented_mixed_anova_example() -> None:
    # pingouin.mixed_anova's docstring (dataset "mixed_anova", dv Scores, between Group, within Time):
    #         Source     SS  DF1  DF2     MS      F  p_unc    np2    eps       ng2
    # 0        Group  5.460    1   58  5.460  5.052  0.028  0.080    NaN     0.031
    # 1         Time  7.628    2  116  3.814  4.027  0.020  0.065  0.998     0.042
    # 2  Interaction  5.167    2  116  2.584  2.728  0.070  0.045  0.998     0.029
    df = pg.read_dataset("mixed_anova")
    values, groups, n_groups, levels = wide_of(df, "Scores", "Group", ["Time"], "Subject")
    table = mixed_anova_table(values, groups, n_groups, levels, ["Time"], "Group").set_index("effect")
    published = {"Group": ("5.460", 1, 58, "5.460", "5.052", "0.028", "0.080", "0.031"),
                 "Time": ("7.628", 2, 116, "3.814", "4.027", "0.020", "0.065", "0.042"),
                 "Group * Time": ("5.167", 2, 116, "2.584", "2.728", "0.070", "0.045", "0.029")}
    for effect, (ss, df1, df2, ms, f, p, np2, ges) in published.items():
        row = table.loc[effect]
        assert (row["df1"], row["df2"]) == (df1, df2)
        for value, printed in ((row["SS"], ss), (row["MS"], ms), (row["F"], f), (row["p"], p),
                               (row["partial_eta2"], np2), (row["ges"], ges)):
            assert agrees(value, printed), (effect, value, printed)
    assert agrees(table.loc["Time", "eps_gg"], "0.998") and table.loc["Time", "correction"] == "HF"
    # the same data through pingouin itself, every digit
    direct = pg.mixed_anova(data=df, dv="Scores", between="Group", within="Time", subject="Subject",
                            effsize="ng2").set_index("Source")
    assert table["F"].to_numpy() == pytest.approx(direct["F"].to_numpy(), rel=1e-10)
    assert table["ges"].to_numpy() == pytest.approx(direct["ng2"].to_numpy(), rel=1e-10)


def test_the_textbook_split_plot_computation_for_three_groups_and_two_within_factors() -> None:
    rng = np.random.default_rng(5)
    rows = []
    for s in range(18):
        group = ("top", "first", "wide")[s % 3]
        person = rng.normal(0, 2)
        for robot, shift in (("fov", 0.0), ("base", 0.8), ("stay", 2.0)):
            for kitchen in ("k1", "k2"):
                true_effect = shift * (1.5 if group == "wide" else 1.0) + (0.5 if kitchen == "k2" else 0.0)
                rows.append({"p": f"s{s}", "view": group, "robot": robot, "kitchen": kitchen,
                             "y": 10 + person + true_effect + rng.normal(0, 1 + (robot == "stay"))})
    long = pd.DataFrame(rows)
    values, groups, n_groups, levels = wide_of(long, "y", "view", ["robot", "kitchen"], "p")
    table = mixed_anova_table(values, groups, n_groups, levels, ["robot", "kitchen"], "view").set_index("effect")
    expected = textbook(long, "y", "view", ["robot", "kitchen"], "p")
    assert set(table.index) == set(expected)
    error_total = expected["view"][1] + sum(expected[e][1] for e in ("robot", "kitchen", "robot * kitchen"))
    for effect, (ss, error, df1, df2) in expected.items():
        row = table.loc[effect]
        assert (row["df1"], row["df2"]) == (df1, df2), effect
        assert [row["SS"], row["SS_error"]] == pytest.approx([ss, error], rel=1e-9), effect
        assert row["F"] == pytest.approx((ss / df1) / (error / df2), rel=1e-9)
        assert row["ges"] == pytest.approx(ss / (ss + error_total), rel=1e-9)
    # sphericity of the within part: the pooled within-group covariance of the robot contrasts
    assert 0.5 <= table.loc["robot", "eps_gg"] <= 1 and table.loc["robot", "eps_gg"] == table.loc["view * robot",
                                                                                                  "eps_gg"]
    assert np.isnan(table.loc["kitchen", "mauchly_W"]), "one df: spherical"


def test_the_eta2g_interval_resamples_within_groups_and_holds_the_estimate() -> None:
    from analysis.statistics.mixed_anova import mixed_ges_bootstrap

    df = pg.read_dataset("mixed_anova")
    values, groups, n_groups, levels = wide_of(df, "Scores", "Group", ["Time"], "Subject")
    table = mixed_anova_table(values, groups, n_groups, levels, ["Time"], "Group")
    first = mixed_ges_bootstrap(values, groups, n_groups, levels, ["Time"], np.random.default_rng(1), 400)
    again = mixed_ges_bootstrap(values, groups, n_groups, levels, ["Time"], np.random.default_rng(1), 400)
    assert first == again, "same seed, same interval"
    for (low, high), ges in zip(first, table["ges"], strict=True):
        assert 0 <= low <= ges <= high <= 1
