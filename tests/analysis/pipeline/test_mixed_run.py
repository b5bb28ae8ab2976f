"""``analyze`` on a mixed design (``--between``), the linear mixed model (``--model lmm``) and the count model of
the interrupts."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pingouin as pg
import pytest
from scipy import stats

from analysis.pipeline.analyze_long import analyze_long
from analysis.preparation.options import AnalysisOptions
from server.cli import main


def test_the_mixed_analysis_and_its_follow_ups(tmp_path) -> None:
    df = pg.read_dataset("mixed_anova")
    result = analyze_long(df, ["Scores"], ["Time"], "Subject", tmp_path, AnalysisOptions(between="Group",
                                                                                        plots=False))
    anova = pd.read_csv(tmp_path / "anova.csv")
    direct = pg.mixed_anova(data=df, dv="Scores", between="Group", within="Time", subject="Subject")
    assert anova["effect"].tolist() == ["Group", "Time", "Group * Time"]
    assert anova["F"].to_numpy() == pytest.approx(direct["F"].to_numpy(), rel=1e-10)
    simple = pd.read_csv(tmp_path / "simple_effects.csv").set_index(["factor", "at"])
    june = df[df["Time"] == "June"]
    ref = stats.f_oneway(*(june.loc[june["Group"] == g, "Scores"] for g in ("Control", "Meditation")))
    assert simple.loc[("Group", "Time=June"), "F"] == pytest.approx(ref.statistic, rel=1e-10)
    # the default pools the within-group covariance (N − G = 58 df): tests/analysis/followups/test_mixed_conventions.py
    assert simple.loc[("Time", "Group=Meditation"), "df2"] == 58
    assert simple.loc[("Group", "Time=June"), "mean_diff"] == pytest.approx(
        june.loc[june["Group"] == "Control", "Scores"].mean()
        - june.loc[june["Group"] == "Meditation", "Scores"].mean())
    pairs = pd.read_csv(tmp_path / "pairwise.csv")
    assert set(pairs["at"]) == {"Group=Control", "Group=Meditation"}
    descriptives = pd.read_csv(tmp_path / "descriptives.csv")
    assert descriptives[["Group", "Time"]].drop_duplicates().shape[0] == 6
    report = (tmp_path / "report.md").read_text()
    assert "mixed (split-plot) ANOVA" in report and "Main effect of Group" in report
    assert result.measures[0].testable


def test_a_between_factor_must_be_one_level_per_participant(tmp_path) -> None:
    from analysis.source.input_errors import AnalysisInputError

    df = pg.read_dataset("mixed_anova")
    df.loc[0, "Group"] = "Meditation" if df.loc[0, "Group"] == "Control" else "Control"
    with pytest.raises(AnalysisInputError, match="more than one level of the between factor"):
        analyze_long(df, ["Scores"], ["Time"], "Subject", tmp_path, AnalysisOptions(between="Group"))


def split_plot(seed: int, missing: int = 0) -> pd.DataFrame:
    rng = np.random.default_rng(seed)
    rows = []
    for s in range(24):
        group = ("top", "first")[s % 2]
        person = rng.normal(0, 3)
        for robot, shift in (("fov", 0.0), ("base", 1.0), ("stay", 2.5)):
            for kitchen in ("k1", "k2"):
                mean = 20 + person + shift + (1.0 if group == "first" else 0) + (0.7 if kitchen == "k2" else 0)
                rows.append({"participant": f"p{s}", "view": group, "robot": robot, "kitchen": kitchen,
                             "ticks": mean + rng.normal(0, 1), "interrupts": rng.poisson(2 + (robot == "stay") * 2)})
    df = pd.DataFrame(rows)
    return df.drop(index=range(0, 6 * missing, 6)) if missing else df


def test_csv_between_with_the_lmm_prints_its_formula_and_agrees_with_the_anova_on_balanced_data(tmp_path,
                                                                                                 capsys) -> None:
    df = split_plot(1)
    path = tmp_path / "cells.csv"
    df.to_csv(path, index=False)
    out = tmp_path / "out"
    assert main(["analyze", "--csv", str(path), "--dv", "ticks,interrupts", "--within", "robot,kitchen",
                 "--between", "view", "--subject", "participant", "--model", "lmm", "--no-plots",
                 "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "linear mixed model: ticks ~ view * robot * kitchen + (1 | participant)" in printed
    lmm = pd.read_csv(out / "lmm.csv")
    anova = pd.read_csv(out / "anova.csv")
    ticks = lmm[lmm["measure"] == "ticks"].set_index("term")
    assert set(ticks.index) == set(anova.loc[anova["measure"] == "ticks", "effect"])
    counts = pd.read_csv(out / "count_model.csv").set_index("term")
    assert counts.loc["robot", "p"] < 0.05 and counts.loc["kitchen", "df"] == 1
    assert counts["model"].iloc[0].startswith("Poisson GEE")
    assert "Poisson GEE" in (out / "report.md").read_text()


def test_on_a_balanced_split_plot_with_one_within_factor_the_lmm_gives_the_anovas_f() -> None:
    """Balanced and complete, one within factor: the random-intercept model's REML variance components are the
    ANOVA's (participants within groups; participant × time within groups), so each term's Wald χ² / df is its
    F."""
    from analysis.statistics.lmm_count_models import lmm_tests

    df = pg.read_dataset("mixed_anova")
    rows = pd.DataFrame(lmm_tests(df, "Scores", ["Group", "Time"], "Subject")).set_index("term")
    direct = pg.mixed_anova(data=df, dv="Scores", between="Group", within="Time", subject="Subject")
    for effect, f, df1 in zip(["Group", "Time", "Group * Time"], direct["F"], direct["DF1"], strict=True):
        assert rows.loc[effect, "chi2"] / df1 == pytest.approx(f, rel=1e-4), effect


def test_the_lmm_keeps_participants_with_a_missing_cell(tmp_path) -> None:
    df = split_plot(2, missing=3)
    result = analyze_long(df, ["ticks"], ["robot", "kitchen"], "participant", tmp_path,
                          AnalysisOptions(between="view", plots=False, lmm=True))
    lmm = pd.read_csv(tmp_path / "lmm.csv")
    assert result.measures[0].n_used == 21 and (lmm["n_subjects"] == 24).all() and (lmm["n_obs"] == 141).all()
    assert result.formulas == ("ticks ~ view * robot * kitchen + (1 | participant)",)


def test_the_per_group_follow_ups_are_each_groups_own_analysis(tmp_path) -> None:
    df = pg.read_dataset("mixed_anova")
    analyze_long(df, ["Scores"], ["Time"], "Subject", tmp_path,
                 AnalysisOptions(between="Group", plots=False, follow_up_error="per-group"))
    simple = pd.read_csv(tmp_path / "simple_effects.csv").set_index(["factor", "at"])
    meditation = df[df["Group"] == "Meditation"]
    rm = pg.rm_anova(data=meditation, dv="Scores", within="Time", subject="Subject", correction=True)
    assert simple.loc[("Time", "Group=Meditation"), "F"] == pytest.approx(rm.at[0, "F"], rel=1e-10)
    pairs = pd.read_csv(tmp_path / "pairwise.csv").set_index(["at", "level_1", "level_2"])
    wide = meditation.pivot(index="Subject", columns="Time", values="Scores")
    paired = stats.ttest_rel(wide["August"], wide["January"])
    assert pairs.loc[("Group=Meditation", "August", "January"), "t"] == pytest.approx(paired.statistic, rel=1e-10)
    assert pairs.loc[("Group=Meditation", "August", "January"), "df"] == 29
