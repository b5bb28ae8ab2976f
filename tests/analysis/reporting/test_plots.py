"""Interaction and paired-lines plots: level order, units, clipped error bars, jitter, one to three factors."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from analysis.preparation.levels import apply_level_order
from analysis.preparation.measure_info import MeasureInfo, measure_info
from analysis.reporting.plots import interaction_plot, paired_plot
from analysis.statistics.descriptives import cell_descriptives

WITHIN = ["robot", "kitchen"]


def ordered(df: pd.DataFrame, within: list[str] = WITHIN) -> pd.DataFrame:
    return apply_level_order(df, within, {"robot": ["fov_aware", "baseline"]})


def test_interaction_plot_writes_png_and_svg_with_units_and_the_error_bar_caption(cells, tmp_path) -> None:
    df = ordered(cells())
    desc = cell_descriptives(df, "ticks", WITHIN, "participant")
    folder = tmp_path / "plots"
    paths, clipped = interaction_plot(desc, measure_info("ticks", df["ticks"], 400), WITHIN,
                                      folder / "ticks_interaction")
    assert paths == [folder / "ticks_interaction.png", folder / "ticks_interaction.svg"] and not clipped
    png, svg = (p.read_bytes() for p in paths)
    assert png.startswith(b"\x89PNG\r\n\x1a\n")
    text = svg.decode()
    assert "Error bars: within-subject 95% confidence intervals" in text and "Cousineau-Morey" in text
    assert "ticks (world steps)" in text
    assert text.index("robot = fov_aware") < text.index("robot = baseline")  # the study's order, not a-z


def test_error_bars_stop_at_the_natural_bound(tmp_path) -> None:
    rows = [{"s": s, "robot": r, "pct": v} for s in range(6) for r, v in
            (("a", [0.0, 0.0, 1.0, 0.0, 40.0, 0.0][s]), ("b", [99.0, 100.0, 60.0, 100.0, 100.0, 95.0][s]))]
    df = pd.DataFrame(rows)
    desc = cell_descriptives(df, "pct", ["robot"], "s")
    assert desc["ci95_low"].min() < 0 or desc["ci95_high"].max() > 100
    info = MeasureInfo("pct", "%", 0.0, 100.0)
    paths, clipped = interaction_plot(desc, info, ["robot"], tmp_path / "p")
    assert clipped and "Bars cut at the measure" in paths[1].read_text()


def test_paired_plot_panels_and_jitter_on_discrete_scales(cells, tmp_path) -> None:
    df = ordered(cells(n_subjects=5))
    paths = paired_plot(df, measure_info("interrupts", df["interrupts"]), WITHIN, "participant", tmp_path / "p",
                        np.random.default_rng(0))
    svg = paths[1].read_text()
    assert "kitchen=none_3" in svg and "kitchen=mid_2" in svg
    assert "the 5 participants" in svg and "jitter" in svg
    continuous = paired_plot(df, measure_info("ticks", df["ticks"]), WITHIN, "participant", tmp_path / "q",
                             np.random.default_rng(0))
    assert "jitter" not in continuous[1].read_text()


def test_three_factors_get_one_panel_per_level_of_the_third(cells, tmp_path) -> None:
    base = cells()
    df = ordered(pd.concat([base.assign(view=v) for v in ("top_down", "first_person")]), [*WITHIN, "view"])
    desc = cell_descriptives(df, "ticks", [*WITHIN, "view"], "participant")
    paths, _ = interaction_plot(desc, measure_info("ticks", df["ticks"]), [*WITHIN, "view"], tmp_path / "x")
    svg = paths[1].read_text()
    assert svg.index("view = top_down") < svg.index("view = first_person")


def test_same_data_same_bytes(cells, tmp_path) -> None:
    desc = cell_descriptives(cells(), "ticks", WITHIN, "participant")
    info = MeasureInfo("ticks")
    first, _ = interaction_plot(desc, info, WITHIN, tmp_path / "a" / "x")
    second, _ = interaction_plot(desc, info, WITHIN, tmp_path / "b" / "x")
    for a, b in zip(first, second, strict=True):
        assert Path(a).read_bytes() == Path(b).read_bytes()
