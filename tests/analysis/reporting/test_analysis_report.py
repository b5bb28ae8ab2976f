"""The Markdown and HTML report: data quality first, then method, then each measure."""

from __future__ import annotations

import numpy as np
import pandas as pd
from steakhouse_published import reacttime_long

from analysis.pipeline.analyze_long import analyze_long
from analysis.preparation.options import AnalysisOptions
from analysis.reporting.analysis_report import build_report
from analysis.reporting.document import render_markdown
from analysis.reporting.measure_section import apa_sentences
from analysis.reporting.typeset import prose


def test_report_lists_exclusions_sentences_tables_and_plots(cells, tmp_path) -> None:
    df = cells()
    gone = (df["participant"] == "P09") & (df["robot"] == "fov_aware") & (df["kitchen"] == "mid_2")
    df = df[~gone]
    result = analyze_long(df, ["ticks"], ["robot", "kitchen"], "participant", tmp_path)
    md = (tmp_path / "report.md").read_text()
    page = (tmp_path / "report.html").read_text()
    for text in (md, page):
        assert text.index("Data quality") < text.index("Method") < text.index("Results")
        assert "n used = 11 of 12 participants (1 left out by the complete-case rule)" in text
        assert "participant P09: missing cell robot fov_aware, kitchen mid_2" in text
        assert "Main effect of robot: F(1, 10) = " in text
        assert "Effect of robot at kitchen mid_2: F(1, 10) = " in text
        assert "Effect of kitchen at robot baseline: F(1, 10) = " in text
        assert "Holm-adjusted p" in text
        assert "95% CI (within)" in text
    assert "![ticks: ticks_interaction](plots/ticks_interaction.png)" in md
    assert '<img src="plots/ticks_interaction.png"' in page
    assert "| robot * kitchen | 1 | 10 |" in md
    assert "| fov_aware | mid_2 | 11 |" in md
    sentences = apa_sentences(result.measures[0])
    assert len(sentences) == 3 + 4
    assert all(prose(sentence) in md for sentence in sentences)


def test_corrected_degrees_of_freedom_reach_the_sentence_and_the_rule_is_stated(tmp_path) -> None:
    df = reacttime_long()
    df["cell"] = df["noise"] + df["deg"]
    result = analyze_long(df, ["rt"], ["cell"], "subject", tmp_path, AnalysisOptions(plots=False))
    row = result.anova.iloc[0]
    sentence = apa_sentences(result.measures[0])[0]
    assert row["correction"] == "GG"
    assert sentence.startswith(f"Main effect of cell: F({row['df1_gg']:.2f}, {row['df2_gg']:.2f}) = 38.03, p < .001")
    assert sentence.endswith("(Greenhouse–Geisser, ε = .49).")
    md = (tmp_path / "report.md").read_text()
    assert "Greenhouse–Geisser corrected test is read when ε_GG ≤ 0.75" in md
    assert "| cell | 0.031 | 24.64 | 14 | .048 | 0.485 | 0.678 |" in md  # Mauchly's test


def test_a_measure_that_cannot_be_tested_says_so_and_the_others_run(cells, tmp_path) -> None:
    df = cells().assign(flat=1.0)
    result = analyze_long(df, ["flat", "ticks"], ["robot", "kitchen"], "participant", tmp_path,
                          AnalysisOptions(plots=False))
    assert result.warnings == ("flat: not testable: every value is 1, nothing varies",)
    assert not result.measures[0].testable and result.measures[1].testable
    md = (tmp_path / "report.md").read_text()
    assert "- flat: not testable: every value is 1, nothing varies" in md
    assert "Main effect of robot" in md


def test_no_measure_is_said_explicitly(tmp_path) -> None:
    result = analyze_long(pd.DataFrame({"s": [1, 1, 2, 2], "f": ["a", "b"] * 2, "y": np.arange(4.0)}), ["y"], ["f"],
                          "s", tmp_path, AnalysisOptions(plots=False))
    blocks = build_report(result.__class__((), result.tables, (), tmp_path, ()), AnalysisOptions())
    assert "No measure was analysed." in render_markdown(blocks)


def test_the_prose_is_typeset(cells, tmp_path) -> None:
    """A real minus sign, levels in words, brackets inside parentheses, and an η²G with its first digit showing."""
    df = cells()
    df["ticks"] = df["ticks"] - 150
    df = df[~((df["participant"] == "P03") & (df["robot"] == "baseline") & (df["kitchen"] == "mid_2"))]
    analyze_long(df, ["ticks"], ["robot", "kitchen"], "participant", tmp_path, AnalysisOptions(plots=False))
    md = (tmp_path / "report.md").read_text()
    assert "M_diff = −" in md and "M_diff = -" not in md and "[−" in md
    assert "kitchen=" not in md.split("## Method")[0].replace("| robot=", "").replace("| kitchen=", ""), \
        "no factor=level in the prose of the data-quality section"
    assert prose("missing cell robot=a, kitchen=b (main trial 3 abandoned (grace_expired))") == \
        "missing cell robot a, kitchen b (main trial 3 abandoned [grace_expired])"
    assert prose("changed it by -0.481 on 2026-12-07 for P-03, t(9) = -2.10, [-0.36, -.05]") == \
        "changed it by −0.481 on 2026-12-07 for P-03, t(9) = −2.10, [−0.36, −.05]"
    from analysis.statistics.apa import apa_f_sentence

    row = {"df1": 1, "df2": 14, "F": 0.19, "p": 0.666, "ges": 0.0021, "ges_ci_low": 0.0, "ges_ci_high": 0.063}
    assert apa_f_sentence(row) == "F(1, 14) = 0.19, p = .666, η²G = .002, 90% CI [.000, .063]"
    assert apa_f_sentence({**row, "ges": 0.031}).endswith("η²G = .03, 90% CI [.00, .06]")
