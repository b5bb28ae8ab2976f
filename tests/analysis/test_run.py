"""``analyze_long``: all files, exact headers, exclusions, and refusal before writing."""

from __future__ import annotations

import csv

import numpy as np
import pandas as pd
import pytest

from analysis.errors import AnalysisInputError
from analysis.run import analyze_long

WITHIN = ["robot", "kitchen"]
HEADERS = {
    "anova.csv": ["measure", "effect", "df1", "df2", "SS", "F", "p", "ges", "partial_eta2"],
    "simple_effects.csv": ["measure", "level", "effect", "df1", "df2", "F", "p", "p_holm", "ges"],
    "descriptives.csv": [
        "measure", "robot", "kitchen", "n", "mean", "sd", "se_ws", "ci95_low", "ci95_high",
    ],
    "excluded.csv": ["measure", "subject", "reason"],
}
PLOTS = [
    f"plots/{m}_{kind}.{ext}"
    for m in ("ticks", "interrupts")
    for kind in ("interaction", "paired")
    for ext in ("png", "svg")
]


def header(path) -> list[str]:
    with open(path, newline="", encoding="utf-8") as handle:
        return next(csv.reader(handle))


def test_writes_every_file_with_exact_headers(cells, tmp_path) -> None:
    result = analyze_long(cells(), ["ticks", "interrupts"], WITHIN, "participant", tmp_path / "o")
    out = tmp_path / "o"
    for name, columns in HEADERS.items():
        assert header(out / name) == columns
    for name in [*PLOTS, "report.md", "report.html"]:
        assert (out / name).is_file(), name
    assert sorted(p.relative_to(out).as_posix() for p in result.files) == sorted(
        [*HEADERS, *PLOTS, "report.md", "report.html"]
    )
    anova = pd.read_csv(out / "anova.csv")
    assert anova["measure"].tolist() == ["ticks"] * 3 + ["interrupts"] * 3
    assert anova["effect"].tolist()[:3] == ["robot", "kitchen", "robot * kitchen"]
    assert (anova["df1"] == 1).all() and (anova["df2"] == 11).all()
    simple = pd.read_csv(out / "simple_effects.csv")
    assert simple["effect"].eq("robot").all()
    assert simple["level"].tolist() == ["mid_2", "none_3"] * 2
    assert len(pd.read_csv(out / "descriptives.csv")) == 8
    assert pd.read_csv(out / "excluded.csv").empty


def test_excluded_subjects_are_per_measure(cells, tmp_path) -> None:
    df = cells()
    gone = (df["participant"] == "P03") & (df["robot"] == "baseline") & (df["kitchen"] == "mid_2")
    df = df[~gone].copy()
    df.loc[df["participant"] == "P05", "interrupts"] = np.nan
    result = analyze_long(df, ["ticks", "interrupts"], WITHIN, "participant", tmp_path)
    excluded = pd.read_csv(tmp_path / "excluded.csv")
    assert excluded.values.tolist() == [
        ["ticks", "P03", "missing cell robot=baseline, kitchen=mid_2"],
        ["interrupts", "P03", "missing cell robot=baseline, kitchen=mid_2"],
        [
            "interrupts",
            "P05",
            "missing value of interrupts in cell robot=baseline, kitchen=mid_2; "
            "missing value of interrupts in cell robot=baseline, kitchen=none_3; "
            "missing value of interrupts in cell robot=fov_aware, kitchen=mid_2; "
            "missing value of interrupts in cell robot=fov_aware, kitchen=none_3",
        ],
    ]
    assert [m.n_used for m in result.measures] == [11, 10]
    anova = pd.read_csv(tmp_path / "anova.csv")
    assert anova["df2"].tolist() == [10, 10, 10, 9, 9, 9]
    descriptives = pd.read_csv(tmp_path / "descriptives.csv")
    assert descriptives.groupby("measure")["n"].unique().to_dict() == {
        "interrupts": [10],
        "ticks": [11],
    }


def test_wrong_column_is_refused_before_anything_is_written(cells, tmp_path) -> None:
    with pytest.raises(AnalysisInputError, match="'tiks' not found.*available columns"):
        analyze_long(cells(), ["ticks", "tiks"], WITHIN, "participant", tmp_path / "o")
    assert not (tmp_path / "o").exists()


def test_too_few_complete_subjects(cells, tmp_path) -> None:
    df = cells(n_subjects=2)
    df = df[~((df["participant"] == "P01") & (df["kitchen"] == "mid_2"))]
    with pytest.raises(AnalysisInputError, match="1 subject.*at least 2"):
        analyze_long(df, ["ticks"], WITHIN, "participant", tmp_path)


def test_unsafe_measure_names_become_file_names(cells, tmp_path) -> None:
    df = cells().rename(columns={"ticks": "ticks/trial", "interrupts": "ticks trial"})
    result = analyze_long(df, ["ticks/trial", "ticks trial"], WITHIN, "participant", tmp_path)
    assert result.measures[0].plots[0] == "plots/ticks_trial_interaction.png"
    assert result.measures[1].plots[0] == "plots/ticks_trial_2_interaction.png"
