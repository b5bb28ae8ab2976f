"""The Markdown and HTML report."""

from __future__ import annotations

from analysis.document import render_markdown
from analysis.report import apa_sentences, build_report, write_report
from analysis.run import analyze_long


def test_report_lists_exclusions_sentences_tables_and_plots(cells, tmp_path) -> None:
    df = cells()
    gone = (df["participant"] == "P09") & (df["robot"] == "fov_aware") & (df["kitchen"] == "mid_2")
    df = df[~gone]
    result = analyze_long(df, ["ticks"], ["robot", "kitchen"], "participant", tmp_path)
    md = (tmp_path / "report.md").read_text()
    page = (tmp_path / "report.html").read_text()
    for text in (md, page):
        assert "n used = 11 of 12 subjects (1 excluded)" in text
        assert "subject P09: missing cell robot=fov_aware, kitchen=mid_2" in text
        assert "Main effect of robot: F(1, 10) = " in text
        assert "Effect of robot in kitchen = mid_2: F(1, 10) = " in text
        assert "Holm-adjusted p" in text
        assert "within-subject 95% CI" in text
    assert "![ticks: ticks_interaction](plots/ticks_interaction.png)" in md
    assert "![ticks: ticks_paired](plots/ticks_paired.png)" in md
    assert '<img src="plots/ticks_interaction.png"' in page
    assert "| robot * kitchen | 1 | 10 |" in md
    assert "| fov_aware | mid_2 | 11 |" in md
    sentences = apa_sentences(result.measures[0])
    assert len(sentences) == 5
    assert all(sentence in md for sentence in sentences)


def test_no_exclusion_is_said_explicitly(cells, tmp_path) -> None:
    result = analyze_long(cells(), ["ticks"], ["robot", "kitchen"], "participant", tmp_path)
    assert "No subject was excluded." in render_markdown(build_report(result.measures))


def test_empty_report(tmp_path) -> None:
    md, page = write_report([], tmp_path)
    assert "No measure was analysed." in md.read_text()
    assert "No measure was analysed." in page.read_text()
