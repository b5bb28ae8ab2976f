"""Interaction and paired-lines plots."""

from __future__ import annotations

from pathlib import Path

from analysis.descriptives import cell_descriptives
from analysis.plots import interaction_plot, paired_plot

WITHIN = ["robot", "kitchen"]


def test_interaction_plot_writes_png_and_svg_with_the_error_bar_caption(cells, tmp_path) -> None:
    desc = cell_descriptives(cells(), "ticks", WITHIN, "participant")
    folder = tmp_path / "plots"
    paths = interaction_plot(desc, "ticks", WITHIN, folder / "ticks_interaction")
    assert paths == [folder / "ticks_interaction.png", folder / "ticks_interaction.svg"]
    png, svg = (p.read_bytes() for p in paths)
    assert png.startswith(b"\x89PNG\r\n\x1a\n")
    text = svg.decode()
    assert "Error bars: within-subject 95% confidence intervals" in text
    assert "Cousineau-Morey" in text
    for label in ("mid_2", "none_3", "robot = baseline", "robot = fov_aware"):
        assert label in text


def test_paired_plot_has_one_panel_per_kitchen(cells, tmp_path) -> None:
    paths = paired_plot(cells(n_subjects=5), "ticks", WITHIN, "participant", tmp_path / "p")
    svg = paths[1].read_text()
    assert "kitchen = mid_2" in svg and "kitchen = none_3" in svg
    assert "the 5 participants" in svg


def test_same_data_same_bytes(cells, tmp_path) -> None:
    desc = cell_descriptives(cells(), "ticks", WITHIN, "participant")
    first = interaction_plot(desc, "ticks", WITHIN, tmp_path / "a" / "x")
    second = interaction_plot(desc, "ticks", WITHIN, tmp_path / "b" / "x")
    for a, b in zip(first, second, strict=True):
        assert Path(a).read_bytes() == Path(b).read_bytes()
