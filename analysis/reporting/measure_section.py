"""One measure's section of the report: who was analysed, ready-to-paste sentences, the ANOVA (uncorrected and
corrected, with the error term and effect-size intervals), Mauchly's test, simple effects in every direction,
pairwise comparisons, rank tests for ratings, descriptives and the plots."""

from __future__ import annotations

import math
from pathlib import Path

import pandas as pd

from analysis.reporting.document import Block, BulletList, Heading, Image, Paragraph
from analysis.reporting.report_tables import (
    anova_table,
    descriptives_table,
    interval,
    number,
    pairwise_table,
    rank_table,
    simple_table,
    sphericity_table,
)
from analysis.statistics.apa import apa_f_sentence, format_df, format_proportion, p_clause
from analysis.statistics.results import MeasureResult


def measure_section(result: MeasureResult) -> list[Block]:
    """The blocks for one measure."""
    blocks: list[Block] = [
        Heading(2, result.info.label),
        Paragraph(f"n used = {result.n_used} of {result.n_total} participants ({len(result.excluded)} left out "
                  "by the complete-case rule)."),
    ]
    if result.excluded.empty:
        blocks.append(Paragraph("No participant was left out of this measure."))
    else:
        blocks += [Paragraph("Left out of this measure:"), BulletList(tuple(
            f"participant {r.subject}: {r.reason}" for r in result.excluded.itertuples()))]
    if result.notes:
        blocks += [Paragraph("Notes:"), BulletList(result.notes)]
    if not result.testable:
        if not result.descriptives.empty:
            blocks += [Heading(3, "Descriptives"), descriptives_table(result.descriptives, result.within)]
        return blocks
    blocks += [Heading(3, "Results"), BulletList(tuple(apa_sentences(result)))]
    blocks += [Heading(3, "Repeated-measures ANOVA"), anova_table(result.anova)]
    spherical = sphericity_table(result.anova)
    if spherical is not None:
        blocks += [Heading(3, "Sphericity (Mauchly's test)"), spherical]
    if not result.simple_effects.empty:
        blocks += [Heading(3, "Simple main effects (p Holm-adjusted within each factor)"),
                   simple_table(result.simple_effects)]
    if not result.pairwise.empty:
        blocks += [Heading(3, "Pairwise comparisons (paired t, Holm within each factor and level of the others)"),
                   pairwise_table(result.pairwise)]
    if not result.rank_tests.empty:
        blocks += [Heading(3, "Rank tests (ordinal ratings)"), rank_table(result.rank_tests)]
    blocks += [Heading(3, "Descriptives"), descriptives_table(result.descriptives, result.within)]
    if result.plots:
        blocks.append(Heading(3, "Plots"))
        blocks += [Image(path, f"{result.measure}: {Path(path).stem}") for path in result.plots
                   if path.endswith(".png")]
        svgs = ", ".join(p for p in result.plots if p.endswith(".svg"))
        blocks.append(Paragraph("Interaction plot error bars: within-subject 95% CIs (Cousineau-Morey). "
                                f"SVG versions: {svgs}."))
    return blocks


def apa_sentences(result: MeasureResult) -> list[str]:
    """One sentence per ANOVA effect, simple effect, pairwise comparison and rank test."""
    names = {f: f"Main effect of {f}" for f in result.within}
    lines = [f"{names.get(str(row['effect']), 'Interaction ' + str(row['effect']).replace(' * ', ' × '))}: "
             f"{apa_f_sentence(row)}." for _, row in result.anova.iterrows()]
    for _, row in result.simple_effects.iterrows():
        holm = "" if math.isnan(float(row["p_holm"])) else f" (Holm-adjusted {p_clause(float(row['p_holm']))})"
        difference = ""
        if not pd.isna(row["mean_diff"]):
            difference = (f"; {row['level_1']} − {row['level_2']}: M_diff = {number(row['mean_diff'])}, 95% CI "
                          f"{interval(row['ci95_low'], row['ci95_high'])}{_dz(row['dz'])}")
        lines.append(f"Effect of {row['factor']} at {_at(str(row['at']))}: {apa_f_sentence(row)}{holm}{difference}.")
    for _, row in result.pairwise.iterrows():
        where = f" at {_at(str(row['at']))}" if row["at"] else ""
        if row["note"]:
            lines.append(f"{row['level_1']} vs {row['level_2']}{where}: {row['note']}.")
            continue
        lines.append(
            f"{row['level_1']} vs {row['level_2']}{where}: M_diff = {number(row['mean_diff'])}, 95% CI "
            f"{interval(row['ci95_low'], row['ci95_high'])}, t({format_df(float(row['df']))}) = "
            f"{number(row['t'], 2)}, {p_clause(float(row['p']))} (Holm-adjusted {p_clause(float(row['p_holm']))})"
            + (f", d_z = {number(row['dz'], 2)}, 95% CI {interval(row['dz_ci_low'], row['dz_ci_high'], digits=2)}."
               if not pd.isna(row["dz"]) else "."))
    for _, row in result.rank_tests.iterrows():
        if row["note"]:
            lines.append(f"{row['test']} ({row['factor']}): {row['note']}.")
        elif row["test"] == "Friedman":
            lines.append(f"Friedman ({row['factor']}): χ²({int(row['df'])}) = {float(row['statistic']):.2f}, "
                         f"{p_clause(float(row['p']))}, Kendall's W = {format_proportion(float(row['effect_size']))}.")
        else:
            lines.append(f"Wilcoxon signed-rank ({row['factor']}: {row['levels']}): V = {float(row['statistic']):g}, "
                         f"{p_clause(float(row['p']))}, r = {format_proportion(float(row['effect_size']))}.")
    return lines


def _dz(dz: object) -> str:
    """``, d_z = 0.47`` (empty for a difference between groups, which has none)."""
    return "" if pd.isna(dz) else f", d_z = {number(dz, 2)}"


def _at(label: str) -> str:
    """``fov_angle=90, kitchen=none_3`` → ``fov_angle=90 and kitchen=none_3`` (the typesetting writes the levels
    as words)."""
    parts = label.split(", ")
    return label if len(parts) < 2 else ", ".join(parts[:-1]) + " and " + parts[-1]


def normality_line(result: MeasureResult) -> str:
    """``ticks: W = .973, p = .412 (96 residuals)`` or the reason it was not tested."""
    n = result.normality
    if n.note:
        return f"{result.measure}: {n.note}"
    return f"{result.measure}: W = {format_proportion(n.w, 3)}, {p_clause(n.p)} ({n.n_residuals} residuals)"
