"""The analysis report, in Markdown and HTML, built from the per-measure results.

Per measure: who was analysed and who was excluded (with the reason), ready-to-paste APA sentences,
the two-way RM-ANOVA table, the simple main effects of the first factor within each level of the
second (Holm-adjusted), the cell descriptives with within-subject 95 % CIs, and the plots (paths
relative to the report, so the output folder can be moved or zipped as a whole).
"""

from __future__ import annotations

import importlib.metadata
import math
from collections.abc import Sequence
from pathlib import Path

import pandas as pd

from analysis.apa import apa_f_sentence, format_df, format_p, format_proportion, p_clause
from analysis.document import Block, BulletList, Heading, Image, Paragraph, render_html
from analysis.document import render_markdown, table
from analysis.results import MeasureResult

TITLE = "Repeated-measures analysis"


def build_report(results: Sequence[MeasureResult]) -> list[Block]:
    """The blocks of the whole report: a methods note, then one section per measure."""
    if not results:
        return [Heading(1, TITLE), Paragraph("No measure was analysed.")]
    first = results[0]
    a, b = first.within
    blocks: list[Block] = [
        Heading(1, TITLE),
        Paragraph(
            f"Design: {a} × {b}, both within subjects (subject column: {first.subject}). "
            f"Each measure was analysed with a two-way repeated-measures ANOVA ({a}, {b}, "
            f"{a} × {b}), followed by simple main effects of {a} within each level of {b} "
            "(one-way repeated-measures ANOVAs, p Holm-adjusted across the levels of "
            f"{b}). Subjects without a value in every cell of a measure were excluded from "
            "that measure (complete cases)."
        ),
        Paragraph(
            "Effect sizes: generalized eta squared η²G (Olejnik & Algina, 2003; Bakeman, 2005) "
            "and partial eta squared. Error bars and CIs: within-subject 95% confidence "
            "intervals (Cousineau, 2005, with the Morey, 2008, correction). "
            f"Computed with {_versions()}."
        ),
    ]
    for result in results:
        blocks += measure_section(result)
    return blocks


def measure_section(result: MeasureResult) -> list[Block]:
    """The blocks for one measure."""
    a, b = result.within
    blocks: list[Block] = [
        Heading(2, result.measure),
        Paragraph(
            f"n used = {result.n_used} of {result.n_total} subjects "
            f"({len(result.excluded)} excluded)."
        ),
    ]
    if result.excluded.empty:
        blocks.append(Paragraph("No subject was excluded."))
    else:
        blocks.append(Paragraph("Excluded subjects:"))
        blocks.append(
            BulletList(
                tuple(f"subject {r.subject}: {r.reason}" for r in result.excluded.itertuples())
            )
        )
    blocks += [Heading(3, "Results"), BulletList(tuple(apa_sentences(result)))]
    blocks += [Heading(3, "Two-way repeated-measures ANOVA"), _anova_table(result.anova)]
    blocks += [
        Heading(3, f"Simple main effects of {a} within each level of {b}"),
        _simple_table(result.simple_effects, b),
    ]
    blocks += [
        Heading(3, "Descriptives (within-subject 95% CI)"),
        _descriptives_table(result.descriptives, result.within),
        Heading(3, "Plots"),
    ]
    pngs = [path for path in result.plots if path.endswith(".png")]
    blocks += [Image(path, f"{result.measure}: {Path(path).stem}") for path in pngs]
    blocks.append(
        Paragraph(
            "Interaction plot error bars: within-subject 95% CIs (Cousineau-Morey). "
            "SVG versions: " + ", ".join(p for p in result.plots if p.endswith(".svg")) + "."
        )
    )
    return blocks


def apa_sentences(result: MeasureResult) -> list[str]:
    """One ready-to-paste sentence per ANOVA effect and per simple main effect."""
    a, b = result.within
    names = {
        a: f"Main effect of {a}",
        b: f"Main effect of {b}",
        f"{a} * {b}": f"Interaction {a} × {b}",
    }
    lines = [
        f"{names.get(row['effect'], row['effect'])}: {apa_f_sentence(row)}."
        for _, row in result.anova.iterrows()
    ]
    for _, row in result.simple_effects.iterrows():
        lines.append(
            f"Effect of {row['effect']} in {b} = {row['level']}: {apa_f_sentence(row)} "
            f"(Holm-adjusted {p_clause(float(row['p_holm']))})."
        )
    return lines


def write_report(results: Sequence[MeasureResult], out_dir: Path) -> tuple[Path, Path]:
    """Write ``report.md`` and ``report.html`` into ``out_dir``; return their paths."""
    blocks = build_report(results)
    md, page = out_dir / "report.md", out_dir / "report.html"
    md.write_text(render_markdown(blocks), encoding="utf-8")
    page.write_text(render_html(blocks, TITLE), encoding="utf-8")
    return md, page


def _anova_table(anova: pd.DataFrame) -> Block:
    columns = ("effect", "df1", "df2", "SS", "MS", "F", "p", "η²G", "partial η²")
    rows = [
        (
            str(r["effect"]),
            format_df(float(r["df1"])),
            format_df(float(r["df2"])),
            _number(r["SS"]),
            _number(r["MS"]),
            _number(r["F"], 2),
            format_p(float(r["p"])),
            format_proportion(float(r["ges"]), 3),
            format_proportion(float(r["partial_eta2"]), 3),
        )
        for _, r in anova.iterrows()
    ]
    return table(columns, rows)


def _simple_table(simple: pd.DataFrame, by: str) -> Block:
    columns = (by, "effect", "df1", "df2", "F", "p", "p (Holm)", "η²G")
    rows = [
        (
            str(r["level"]),
            str(r["effect"]),
            format_df(float(r["df1"])),
            format_df(float(r["df2"])),
            _number(r["F"], 2),
            format_p(float(r["p"])),
            format_p(float(r["p_holm"])),
            format_proportion(float(r["ges"]), 3),
        )
        for _, r in simple.iterrows()
    ]
    return table(columns, rows)


def _descriptives_table(desc: pd.DataFrame, within: Sequence[str]) -> Block:
    columns = (*within, "n", "mean", "sd", "se (within)", "95% CI")
    rows = [
        (
            *(str(r[f]) for f in within),
            str(int(r["n"])),
            _number(r["mean"]),
            _number(r["sd"]),
            _number(r["se_ws"]),
            f"[{_number(r['ci95_low'])}, {_number(r['ci95_high'])}]",
        )
        for _, r in desc.iterrows()
    ]
    return table(columns, rows)


def _number(value: float, digits: int | None = None) -> str:
    """Fixed decimals: 2 for magnitudes of 10 and more, else 3, unless ``digits`` is given."""
    x = float(value)
    if math.isnan(x):
        return "n/a"
    if digits is None:
        digits = 2 if abs(x) >= 10 else 3
    return f"{x:.{digits}f}"


def _versions() -> str:
    names = ("pingouin", "pandas", "numpy", "scipy")
    return ", ".join(f"{name} {importlib.metadata.version(name)}" for name in names)
