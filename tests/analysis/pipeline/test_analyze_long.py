"""``analyze_long``: every file with exact headers, one to three factors, exclusions, and refusal before writing."""

from __future__ import annotations

import csv

import numpy as np
import pandas as pd
import pingouin as pg
import pytest

from analysis.pipeline.analyze_long import analyze_long
from analysis.preparation.options import AnalysisOptions
from analysis.source.input_errors import AnalysisInputError

FAST = AnalysisOptions(plots=False)

WITHIN = ["robot", "kitchen"]
HEADERS = {
    "anova.csv": ["measure", "effect", "df1", "df2", "SS", "SS_error", "MS", "MSE", "F", "p", "ges", "partial_eta2",
                  "partial_eta2_ci_low", "partial_eta2_ci_high", "mauchly_W", "mauchly_chi2", "mauchly_df",
                  "mauchly_p", "eps_gg", "eps_hf", "df1_gg", "df2_gg", "p_gg", "df1_hf", "df2_hf", "p_hf",
                  "correction", "df1_read", "df2_read", "p_read", "note", "ges_ci_low", "ges_ci_high"],
    "simple_effects.csv": ["measure", "factor", "at", "df1", "df2", "MSE", "F", "p", "ges", "eps_gg", "eps_hf",
                           "correction", "df1_read", "df2_read", "p_read", "p_holm", "level_1", "level_2",
                           "mean_diff", "ci95_low", "ci95_high", "dz", "dz_ci_low", "dz_ci_high", "note"],
    "pairwise.csv": ["measure", "factor", "at", "level_1", "level_2", "n", "mean_1", "mean_2", "mean_diff", "se",
                     "ci95_low", "ci95_high", "t", "df", "p", "p_holm", "dz", "dz_ci_low", "dz_ci_high", "note"],
    "rank_tests.csv": ["measure", "factor", "test", "levels", "n", "statistic", "df", "p", "effect_size",
                       "effect_size_name", "note"],
    "descriptives.csv": ["measure", "robot", "kitchen", "n", "mean", "sd", "se_ws", "ci95_low", "ci95_high"],
    "excluded.csv": ["measure", "subject", "reason"],
    "exclusions.csv": ["subject", "cell", "rule", "reason", "included"],
    "normality.csv": ["measure", "n_residuals", "W", "p", "note"],
    "order.csv": ["measure", "n", "positions", "slope", "se", "z", "p", "order_effect", "carryover_chi2",
                  "carryover_df", "carryover_p", "sentence", "note"],
    "count_model.csv": ["measure", "model", "formula", "term", "chi2", "df", "p", "n_obs", "n_subjects", "note"],
}
PLOTS = [f"plots/{m}_{kind}.{ext}" for m in ("ticks", "interrupts") for kind in ("interaction", "paired")
         for ext in ("png", "svg")]


def header(path) -> list[str]:
    with open(path, newline="", encoding="utf-8") as handle:
        return next(csv.reader(handle))


def test_writes_every_file_with_exact_headers(cells, tmp_path) -> None:
    result = analyze_long(cells(), ["ticks", "interrupts"], WITHIN, "participant", tmp_path / "o")
    out = tmp_path / "o"
    for name, columns in HEADERS.items():
        assert header(out / name) == columns, name
    assert sorted(p.relative_to(out).as_posix() for p in result.files) == sorted(
        [*HEADERS, *PLOTS, "report.md", "report.html"])
    anova = pd.read_csv(out / "anova.csv")
    assert anova["measure"].tolist() == ["ticks"] * 3 + ["interrupts"] * 3
    assert anova["effect"].tolist()[:3] == ["robot", "kitchen", "robot * kitchen"]
    assert (anova["df1"] == 1).all() and (anova["df2"] == 11).all() and (anova["correction"] == "none").all()
    simple = pd.read_csv(out / "simple_effects.csv")
    assert list(zip(simple["factor"], simple["at"], strict=True))[:4] == [
        ("robot", "kitchen=none_3"), ("robot", "kitchen=mid_2"), ("kitchen", "robot=baseline"),
        ("kitchen", "robot=fov_aware")]
    assert len(pd.read_csv(out / "descriptives.csv")) == 8
    assert pd.read_csv(out / "excluded.csv").empty and pd.read_csv(out / "pairwise.csv").empty


def test_one_and_three_factors(cells, tmp_path) -> None:
    base = cells()
    one = analyze_long(base[base["kitchen"] == "none_3"], ["ticks"], ["robot"], "participant", tmp_path / "one", FAST)
    assert one.anova["effect"].tolist() == ["robot"] and one.simple_effects.empty
    three = pd.concat([base.assign(view=v, ticks=base["ticks"] + k) for k, v in enumerate(("a", "b", "c"))])
    result = analyze_long(three, ["ticks"], [*WITHIN, "view"], "participant", tmp_path / "three")
    assert len(result.anova) == 7 and result.anova["effect"].iloc[-1] == "robot * kitchen * view"
    pairs = result.tables["pairwise.csv"]
    assert len(pairs) == 3 * (1 + 4)  # the three views: averaged, then in each of the 2 × 2 robot × kitchen cells
    assert (pairs["at"] == "").sum() == 3 and pairs["at"].nunique() == 5
    assert (tmp_path / "three" / "plots" / "ticks_interaction.svg").is_file()


def test_excluded_subjects_are_per_measure(cells, tmp_path) -> None:
    df = cells()
    gone = (df["participant"] == "P03") & (df["robot"] == "baseline") & (df["kitchen"] == "mid_2")
    df = df[~gone].copy()
    df.loc[df["participant"] == "P05", "interrupts"] = np.nan
    result = analyze_long(df, ["ticks", "interrupts"], WITHIN, "participant", tmp_path, FAST)
    excluded = pd.read_csv(tmp_path / "excluded.csv")
    assert excluded.values.tolist()[:2] == [
        ["ticks", "P03", "missing cell robot=baseline, kitchen=mid_2"],
        ["interrupts", "P03", "missing cell robot=baseline, kitchen=mid_2"],
    ]
    assert excluded.values.tolist()[2][2].startswith("missing value of interrupts in cell robot=baseline, kitchen=")
    assert [m.n_used for m in result.measures] == [11, 10]
    assert pd.read_csv(tmp_path / "anova.csv")["df2"].tolist() == [10, 10, 10, 9, 9, 9]


def test_invalid_trials_left_out_unless_included(cells, tmp_path) -> None:
    df = cells().assign(invalid_reason=None, missed_decisions_pct=0.0)
    df.loc[0, ["invalid_reason", "missed_decisions_pct"]] = ["robot missed 9% of its decisions", 9.0]
    left = analyze_long(df, ["ticks"], WITHIN, "participant", tmp_path / "a", FAST)
    assert left.measures[0].n_used == 11 and len(left.tables["exclusions.csv"]) == 1
    assert "excluded: invalid robot trial: robot missed 9%" in left.measures[0].excluded.iloc[0]["reason"]
    kept = analyze_long(df, ["ticks"], WITHIN, "participant", tmp_path / "b",
                        AnalysisOptions(include=frozenset({"invalid"}), plots=False))
    assert kept.measures[0].n_used == 12 and kept.tables["exclusions.csv"]["included"].tolist() == [1]
    md = (tmp_path / "b" / "report.md").read_text()
    assert "robot missed 9% of its decisions" in md and "kept (--include-invalid)" in md


def test_finished_censoring_and_order_tables_when_the_columns_are_there(cells, tmp_path) -> None:
    df = cells().assign(finished=1)
    df["position"] = df.groupby("participant").cumcount() + 1
    df.loc[df.index[:3], "finished"] = 0
    result = analyze_long(df, ["ticks"], WITHIN, "participant", tmp_path, FAST)
    assert result.tables["censoring.csv"]["reached_horizon"].sum() == 3
    assert result.tables["finished.csv"]["test"].iloc[0] == "Cochran's Q"
    assert "censored at the horizon" in " ".join(result.measures[0].notes)
    assert result.tables["order.csv"]["positions"].iloc[0] == 4
    md = (tmp_path / "report.md").read_text()
    assert "3 cell(s) have trials that reached the horizon; in those trials ticks is the horizon" in md
    analyze_long(df, ["interrupts"], WITHIN, "participant", tmp_path / "other", FAST)
    md = (tmp_path / "other" / "report.md").read_text()
    assert "No measure analysed here is capped by it (ticks would be)" in md and "trials ticks" not in md, \
        "the sentence names the measures analysed, not ticks when ticks is not one"


def test_the_published_crash_now_reports_not_testable(tmp_path) -> None:
    # Issue 15: pingouin's rm_anova2 with one level all 0 stopped the old analysis with KeyError: 'F'.
    df = pg.read_dataset("rm_anova2")
    df.loc[df["Metric"] == "Action", "Performance"] = 0
    result = analyze_long(df, ["Performance"], ["Time", "Metric"], "Subject", tmp_path, FAST)
    assert result.warnings == (
        "Performance: simple effect of Time at Metric=Action: not testable: no variance (every value is the same)",)
    assert np.isfinite(result.anova["F"]).all()


def test_wrong_column_or_design_is_refused_before_anything_is_written(cells, tmp_path) -> None:
    with pytest.raises(AnalysisInputError, match=r"'tiks' not found.*available columns"):
        analyze_long(cells(), ["ticks", "tiks"], WITHIN, "participant", tmp_path / "o")
    with pytest.raises(AnalysisInputError, match="one to 3 distinct within factors"):
        analyze_long(cells(), ["ticks"], [*WITHIN, "participant", "x"], "participant", tmp_path / "o")
    with pytest.raises(AnalysisInputError, match="does not list"):
        analyze_long(cells(), ["ticks"], WITHIN, "participant", tmp_path / "o",
                     AnalysisOptions(levels={"robot": ["baseline"]}))
    assert not (tmp_path / "o").exists()


def test_too_few_complete_subjects_is_not_testable(cells, tmp_path) -> None:
    df = cells(n_subjects=2)
    df = df[~((df["participant"] == "P01") & (df["kitchen"] == "mid_2"))]
    result = analyze_long(df, ["ticks"], WITHIN, "participant", tmp_path, FAST)
    assert not result.measures[0].testable
    assert result.warnings[0].startswith("ticks: not testable: 1 participant(s) have a value in every cell")


def test_unsafe_measure_names_become_file_names(cells, tmp_path) -> None:
    df = cells().rename(columns={"ticks": "ticks/trial", "interrupts": "ticks trial"})
    result = analyze_long(df, ["ticks/trial", "ticks trial"], WITHIN, "participant", tmp_path)
    assert result.measures[0].plots[0] == "plots/ticks_trial_interaction.png"
    assert result.measures[1].plots[0] == "plots/ticks_trial_2_interaction.png"


def test_a_constant_measure_has_its_anova_rows_with_the_reason(cells, tmp_path) -> None:
    df = cells().assign(flat=3.0)
    result = analyze_long(df, ["flat", "ticks"], WITHIN, "participant", tmp_path, FAST)
    anova = pd.read_csv(tmp_path / "anova.csv")
    flat = anova[anova["measure"] == "flat"]
    assert flat["effect"].tolist() == ["robot", "kitchen", "robot * kitchen"]
    assert set(flat["note"]) == {"not testable: every value is 3, nothing varies"} and flat["F"].isna().all()
    assert flat["df1"].tolist() == [1, 1, 1]
    assert not result.measures[0].testable and np.isfinite(anova.loc[anova["measure"] == "ticks", "F"]).all()


def test_a_non_numeric_cell_is_named_and_the_other_measures_still_run(cells, tmp_path) -> None:
    df = cells()
    df["ticks"] = df["ticks"].astype(object)
    df.loc[6, "ticks"] = "n/a"
    who = df.loc[6, ["participant", "robot", "kitchen"]].tolist()
    result = analyze_long(df, ["ticks", "interrupts"], WITHIN, "participant", tmp_path, FAST)
    expected = (f"ticks: not testable: 1 value(s) of ticks are not numbers: row 7 (participant {who[0]}, "
                f"robot={who[1]}, kitchen={who[2]}): 'n/a'")
    assert result.warnings == (expected,)
    anova = pd.read_csv(tmp_path / "anova.csv")
    assert anova.loc[anova["measure"] == "ticks", "note"].str.contains("row 7").all()
    assert np.isfinite(anova.loc[anova["measure"] == "interrupts", "F"]).all()
    assert expected.split(": ", 1)[1].replace("=", " ") in (tmp_path / "report.md").read_text()
