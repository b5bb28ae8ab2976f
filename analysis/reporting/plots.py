"""Figures for a design with one to three within factors, drawn with matplotlib's Agg canvas, saved as PNG and SVG.

Figures are built as ``matplotlib.figure.Figure`` objects on an explicit ``FigureCanvasAgg``, never through
``pyplot``, so no global figure state is created and no display is needed. Files are written without
timestamps so that the same data give the same bytes. Levels appear in the study's order (the categorical order
of :mod:`analysis.preparation.levels`); the y axis is labelled with the measure's unit from the data dictionary.

* ``interaction_plot``: cell means with within-subject 95 % CIs (Cousineau–Morey, see
  ``analysis.statistics.descriptives``) as error bars, cut at the measure's natural bounds (a note says so); the caption
  says what the bars are, because bars of another kind would be read differently (Cumming & Finch 2005). One
  factor: the factor on x. Two: the second on x, one line per level of the first. Three: one panel per level of
  the third.
* ``paired_plot``: one line per participant joining their values across the levels of the first factor, one
  panel per combination of the others, the cell means on top. On a discrete scale (counts, ratings) each
  participant's points are shifted sideways by a small random offset (drawn from the generator passed in) so that
  equal values stay visible.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from pathlib import Path

import matplotlib as mpl
import numpy as np
import pandas as pd
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator

from analysis.preparation.cells import factor_levels
from analysis.preparation.measure_info import MeasureInfo
from analysis.source.naming import cell_label

CI_CAPTION = (
    "Points: cell means. Error bars: within-subject 95% confidence intervals "
    "(Cousineau-Morey method, Morey 2008 correction)."
)
JITTER = 0.12
_SVG_SALT = "steakhouse-analysis"


def interaction_plot(descriptives: pd.DataFrame, info: MeasureInfo, within: Sequence[str], stem: Path
                     ) -> tuple[list[Path], bool]:
    """Draw the cell means of ``descriptives`` (see ``cell_descriptives``); returns the PNG and SVG paths and
    whether an error bar was cut at a natural bound."""
    within = list(within)
    x_factor = within[1] if len(within) > 1 else within[0]
    trace = within[0] if len(within) > 1 else None
    panels = factor_levels(descriptives, within[2]) if len(within) > 2 else [None]
    fig = _figure(max(5.5, 3.6 * len(panels)), 4.2)
    axes = fig.subplots(1, len(panels), sharey=True, squeeze=False)[0]
    x_levels = factor_levels(descriptives, x_factor)
    clipped = False
    for ax, panel in zip(axes, panels, strict=True):
        part = descriptives if panel is None else descriptives[descriptives[within[2]] == panel]
        traces = factor_levels(part, trace) if trace else [None]
        width = 0.08 * (len(traces) - 1)
        for i, level in enumerate(traces):
            rows = (part if level is None else part[part[trace] == level]).set_index(x_factor).loc[x_levels]
            bounds = [info.clip(lo, hi) for lo, hi in zip(rows["ci95_low"], rows["ci95_high"], strict=True)]
            clipped |= any(cut for _, _, cut in bounds)
            means = rows["mean"].to_numpy(dtype=float)
            errors = [means - [b[0] for b in bounds], [b[1] for b in bounds] - means]
            offset = -width / 2 + (width * i / max(len(traces) - 1, 1))
            ax.errorbar([k + offset for k in range(len(x_levels))], means, yerr=errors, marker="o", capsize=4,
                        label=None if level is None else f"{trace} = {level}")
        _x_axis(ax, x_levels, x_factor, pad=0.5)
        if panel is not None:
            ax.set_title(f"{within[2]} = {panel}")
    axes[0].set_ylabel(info.label)
    if trace:
        axes[0].legend(frameon=False)
    caption = CI_CAPTION + (" Bars cut at the measure's natural bound." if clipped else "")
    fig.suptitle(f"{info.name}: {' × '.join(within)}")
    fig.text(0.5, 0.01, caption, ha="center", va="bottom", fontsize=7, wrap=True)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    return save_figure(fig, stem), clipped


def paired_plot(df: pd.DataFrame, info: MeasureInfo, within: Sequence[str], subject: str, stem: Path,
                rng: np.random.Generator) -> list[Path]:
    """One line per participant across the levels of ``within[0]``, one panel per cell of the other factors."""
    within = list(within)
    x_factor, others = within[0], within[1:]
    x_levels = factor_levels(df, x_factor)
    panels = list(itertools.product(*(factor_levels(df, f) for f in others)))
    fig = _figure(max(5.0, 3.2 * len(panels) + 0.6), 4.0)
    axes = fig.subplots(1, len(panels), sharey=True, squeeze=False)[0]
    position = {level: k for k, level in enumerate(x_levels)}
    subjects = list(pd.unique(df[subject]))
    shift = dict(zip(subjects, rng.uniform(-JITTER, JITTER, len(subjects)) if info.discrete
                     else np.zeros(len(subjects)), strict=True))
    for ax, combo in zip(axes, panels, strict=True):
        part = df
        for factor, level in zip(others, combo, strict=True):
            part = part[part[factor] == level]
        for who, rows in part.groupby(subject, sort=False, observed=True):
            xs = rows[x_factor].map(position).astype(float) + shift[who]
            order = np.argsort(xs.to_numpy())
            ax.plot(xs.to_numpy()[order], rows[info.name].to_numpy(dtype=float)[order], color="0.55", alpha=0.6,
                    linewidth=0.9, marker=".")
        means = part.groupby(x_factor, observed=True)[info.name].mean().reindex(x_levels)
        ax.plot(range(len(x_levels)), means, color="C3", linewidth=2.5, marker="o", label="mean")
        _x_axis(ax, x_levels, x_factor, pad=0.4)
        if others:
            ax.set_title(cell_label(others, combo))
    axes[0].set_ylabel(info.label)
    if info.discrete:
        axes[0].yaxis.set_major_locator(MaxNLocator(integer=True))
    axes[0].legend(frameon=False)
    note = f"Grey lines: the {len(subjects)} participants; red: cell means."
    if info.discrete:
        note += " Points shifted sideways at random (jitter) so that equal values stay visible."
    fig.text(0.5, 0.01, note, ha="center", va="bottom", fontsize=7, wrap=True)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    return save_figure(fig, stem)


def save_figure(fig: Figure, stem: Path) -> list[Path]:
    """Write ``fig`` to ``stem.png`` (150 dpi) and ``stem.svg`` (text as text), no timestamps."""
    stem.parent.mkdir(parents=True, exist_ok=True)
    png, svg = (stem.parent / f"{stem.name}.{ext}" for ext in ("png", "svg"))
    fig.savefig(png, format="png", dpi=150, metadata={"Software": None})
    with mpl.rc_context({"svg.hashsalt": _SVG_SALT, "svg.fonttype": "none"}):
        fig.savefig(svg, format="svg", metadata={"Date": None})
    return [png, svg]


def _x_axis(ax: Axes, levels: Sequence[object], name: str, pad: float) -> None:
    ax.set_xticks(range(len(levels)), [str(level) for level in levels])
    ax.set_xlim(-pad, len(levels) - 1 + pad)
    ax.set_xlabel(name)


def _figure(width: float, height: float) -> Figure:
    fig = Figure(figsize=(width, height))
    FigureCanvasAgg(fig)
    return fig
