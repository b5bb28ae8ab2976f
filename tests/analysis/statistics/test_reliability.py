"""Cronbach's α of questionnaire scales (analysis.statistics.reliability), and scales analysed as rating measures."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pingouin as pg
import pytest

from analysis.source.study_design import RatingItem, ScaleSpec
from analysis.statistics.anova import rm_anova
from analysis.statistics.reliability import RELIABILITY_COLUMNS, cronbach, scale_reliability

ITEMS = (RatingItem("q.a", 1, 7), RatingItem("q.b", 1, 7, reverse=True), RatingItem("q.c", 1, 7))
SCALE = ScaleSpec("q.fluency", "Fluency", ("q.a", "q.b", "q.c"))


def test_alpha_matches_r_psych() -> None:
    # R psych::alpha on pingouin's cronbach_alpha dataset (real-statistics.com), as recorded in pingouin's
    # tests/test_reliability.py: α = .592, Feldt 95% CI [.195, .840].
    wide = pg.read_dataset("cronbach_alpha").pivot(index="Subj", columns="Items", values="Scores")
    out = cronbach(wide)
    assert isinstance(out["alpha"], float)
    assert round(out["alpha"], 3) == 0.592 and (out["ci95_low"], out["ci95_high"]) == (0.195, 0.840)


def test_alpha_is_hoyts_anova_reliability() -> None:
    # Hoyt (1941): α = 1 − MS(participant × item) / MS(participant), from the participant × item ANOVA.
    wide = pg.read_dataset("cronbach_alpha").pivot(index="Subj", columns="Items", values="Scores").dropna()
    long = wide.reset_index().melt(id_vars="Subj", var_name="item", value_name="score")
    row = rm_anova(long, "score", ["item"], "Subj").iloc[0]
    ms_subjects = wide.sum(axis=1).var(ddof=1) / wide.shape[1]
    assert cronbach(wide)["alpha"] == pytest.approx(1 - row["MSE"] / ms_subjects)


def test_reliability_pooled_and_per_condition_with_reversed_items() -> None:
    rng = np.random.default_rng(4)
    rows = []
    for s in range(12):
        trait = rng.normal(4, 1.2)
        for robot in ("fov_aware", "baseline"):
            answers = np.clip(np.round(trait + rng.normal(0, 0.7, 3)), 1, 7)
            rows.append({"participant": s, "robot": robot, "q.a": answers[0], "q.b": 8 - answers[1],
                         "q.c": answers[2]})
    cells = pd.DataFrame(rows)
    table = scale_reliability(cells, ITEMS, (SCALE,), ["robot"])
    assert list(table.columns) == RELIABILITY_COLUMNS
    assert table["condition"].tolist() == ["all conditions", "robot=fov_aware", "robot=baseline"]
    assert table["n"].tolist() == [24, 12, 12] and (table["items"] == 3).all()
    from analysis.preparation.levels import apply_level_order

    study_order = apply_level_order(cells.iloc[::-1], ["robot"], {"robot": ["fov_aware", "baseline"]})
    assert scale_reliability(study_order, ITEMS, (SCALE,), ["robot"])["condition"].tolist()[1:] == [
        "robot=fov_aware", "robot=baseline"], "the study's order, not the rows' order"
    unreversed = scale_reliability(cells, (ITEMS[0], RatingItem("q.b", 1, 7), ITEMS[2]), (SCALE,), ["robot"])
    assert table.loc[0, "alpha"] > 0.6 > unreversed.loc[0, "alpha"]


def test_alpha_needs_two_items_and_variance() -> None:
    single = scale_reliability(pd.DataFrame({"q.a": [1, 2, 3]}), ITEMS, (ScaleSpec("q.s", "S", ("q.a",)),), [])
    assert single.loc[0, "note"] == "not applicable: α needs at least two items"
    note = cronbach(pd.DataFrame({"a": [3, 3, 3, 3], "b": [2, 2, 2, 2]}))["note"]
    assert isinstance(note, str) and note.startswith("not computable")


def test_scales_are_scored_and_analysed_as_rating_measures(tmp_path) -> None:
    from analysis.pipeline.analyze_long import analyze_long
    from analysis.preparation.options import AnalysisOptions

    rng = np.random.default_rng(9)
    rows = []
    for s in range(10):
        trait = rng.normal(4, 1)
        for shift, robot in ((0.0, "fov_aware"), (1.0, "baseline"), (0.5, "stay")):
            a, b, c = np.clip(np.round(trait + shift + rng.normal(0, 0.6, 3)), 1, 7)
            rows.append({"participant": s, "robot": robot, "q.a": a, "q.b": 8 - b, "q.c": c})
    options = AnalysisOptions(items=ITEMS, scales=(SCALE,), ratings={"q.fluency": (1.0, 7.0)}, plots=False)
    result = analyze_long(pd.DataFrame(rows), ["q.fluency"], ["robot"], "participant", tmp_path, options)
    assert result.measures[0].info.rating and result.measures[0].n_used == 10
    assert result.tables["rank_tests.csv"]["test"].tolist() == ["Friedman"]
    assert result.tables["reliability.csv"]["condition"].tolist()[0] == "all conditions"
    md = (tmp_path / "report.md").read_text()
    assert "## Questionnaire scales" in md and "Friedman (robot): χ²(2) = " in md
