"""Figures for a two-way within design, drawn with matplotlib's Agg canvas and saved as PNG and SVG.

Figures are built as ``matplotlib.figure.Figure`` objects on an explicit ``FigureCanvasAgg``, never
through ``pyplot``, so no global figure state is created and no display is needed. Files are
written without timestamps so that the same data give the same bytes.

* ``interaction_plot``: the second factor (the kitchen) on x, one line per level of the first (the
  robot), cell means with within-subject 95 % CIs (Cousineau–Morey, see ``analysis.descriptives``)
  as error bars; the caption says so, because bars of another kind would be read differently
  (Cumming & Finch 2005).
* ``paired_plot``: one panel per kitchen, one line per participant joining their values under
  each robot, with the cell means on top: shows what the ANOVA summarises.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import matplotlib as mpl
import pandas as pd
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from analysis.cells import factor_levels

CI_CAPTION = (
    "Points: cell means. Error bars: within-subject 95% confidence intervals "
    "(Cousineau-Morey method, Morey 2008 correction)."
)
_SVG_SALT = "steakhouse-analysis"


def interaction_plot(
    descriptives: pd.DataFrame, dv: str, within: Sequence[str], stem: Path
) -> list[Path]:
    """Draw ``dv`` by ``within[1]`` (x) with one line per level of ``within[0]``; save PNG and SVG.

    ``descriptives`` is the table of ``analysis.descriptives.cell_descriptives``. Returns the paths
    written, ``stem`` with ``.png`` and ``.svg`` appended.
    """
    trace, x_factor = within
    x_levels = factor_levels(descriptives, x_factor)
    trace_levels = factor_levels(descriptives, trace)
    fig = _figure(5.5, 4.2)
    ax = fig.add_subplot()
    width = 0.08 * (len(trace_levels) - 1)
    for i, level in enumerate(trace_levels):
        rows = descriptives[descriptives[trace] == level].set_index(x_factor).loc[x_levels]
        offset = -width / 2 + (width * i / max(len(trace_levels) - 1, 1))
        xs = [k + offset for k in range(len(x_levels))]
        ax.errorbar(
            xs,
            rows["mean"],
            yerr=[rows["mean"] - rows["ci95_low"], rows["ci95_high"] - rows["mean"]],
            marker="o",
            capsize=4,
            label=f"{trace} = {level}",
        )
    ax.set_xticks(range(len(x_levels)), [str(level) for level in x_levels])
    ax.set_xlim(-0.5, len(x_levels) - 0.5)
    ax.set_xlabel(x_factor)
    ax.set_ylabel(dv)
    ax.set_title(f"{dv}: {trace} × {x_factor}")
    ax.legend(frameon=False)
    fig.text(0.5, 0.01, CI_CAPTION, ha="center", va="bottom", fontsize=7, wrap=True)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    return save_figure(fig, stem)


def paired_plot(
    df: pd.DataFrame, dv: str, within: Sequence[str], subject: str, stem: Path
) -> list[Path]:
    """One panel per level of ``within[1]``, a line per subject across the levels of ``within[0]``.

    ``df`` is the complete long table. Returns the PNG and SVG paths written.
    """
    x_factor, panel_factor = within
    x_levels = factor_levels(df, x_factor)
    panels = factor_levels(df, panel_factor)
    fig = _figure(3.2 * len(panels) + 0.6, 4.0)
    axes = fig.subplots(1, len(panels), sharey=True, squeeze=False)[0]
    position = {level: k for k, level in enumerate(x_levels)}
    for ax, panel in zip(axes, panels, strict=True):
        part = df[df[panel_factor] == panel]
        for _, rows in part.groupby(subject, sort=True, observed=True):
            rows = rows.assign(_x=rows[x_factor].map(position)).sort_values("_x")
            ax.plot(rows["_x"], rows[dv], color="0.55", alpha=0.6, linewidth=0.9, marker=".")
        means = part.groupby(x_factor, observed=True)[dv].mean().reindex(x_levels)
        ax.plot(range(len(x_levels)), means, color="C3", linewidth=2.5, marker="o", label="mean")
        ax.set_xticks(range(len(x_levels)), [str(level) for level in x_levels])
        ax.set_xlim(-0.4, len(x_levels) - 0.6)
        ax.set_xlabel(x_factor)
        ax.set_title(f"{panel_factor} = {panel}")
    axes[0].set_ylabel(dv)
    axes[0].legend(frameon=False)
    n = df[subject].nunique()
    fig.text(
        0.5, 0.01, f"Grey lines: the {n} participants; red: cell means.", ha="center", fontsize=7
    )
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


def _figure(width: float, height: float) -> Figure:
    fig = Figure(figsize=(width, height))
    FigureCanvasAgg(fig)
    return fig
