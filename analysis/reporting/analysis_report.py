"""The analysis report, in Markdown and HTML: data quality first, then the method, the analysis of ``finished`` and
of the questionnaire scales, then one section per measure (:mod:`analysis.reporting.measure_section`).

Plot paths are relative to the report, so the output folder can be moved or zipped as a whole.
"""

from __future__ import annotations

import importlib.metadata
from pathlib import Path

import pandas as pd

from analysis.preparation.options import PER_GROUP, POOLED, AnalysisOptions
from analysis.reporting.document import Block, BulletList, Heading, Paragraph, render_html, render_markdown, table
from analysis.reporting.end_section import end_of_study_section
from analysis.reporting.measure_section import measure_section
from analysis.reporting.quality_section import ReportContext, quality_section
from analysis.reporting.report_tables import interval, number
from analysis.reporting.typeset import typeset
from analysis.statistics.anova import GG_THRESHOLD
from analysis.statistics.apa import format_p, format_proportion
from analysis.statistics.effect_sizes import BOOTSTRAP_RESAMPLES
from analysis.statistics.results import AnalysisResult

SS_TYPE_TEXT = {3: "type III sums of squares, as afex", 2: "type II sums of squares, as pingouin"}
FOLLOW_UP_TEXT = {
    POOLED: "on the within-group covariance pooled over the groups (t and F on N − G df, as emmeans on an afex "
            "model; the F of a factor with more than two levels is emmeans' joint test, without a sphericity "
            "correction)",
    PER_GROUP: "on that group's participants alone (paired t and one-way repeated-measures ANOVAs on n − 1 df "
               "within the group)",
}
"""How the Method paragraph names a mixed design's conventions
(:class:`analysis.preparation.options.AnalysisOptions`)."""


def build_report(result: AnalysisResult, options: AnalysisOptions, context: ReportContext | None = None
                 ) -> list[Block]:
    """Every block of the report."""
    blocks: list[Block] = [Heading(1, options.title)]
    if not result.measures:
        return [*blocks, Paragraph("No measure was analysed.")]
    blocks += quality_section(result, context)
    blocks += method_section(result, options)
    blocks += finished_section(result.tables.get("finished.csv"))
    blocks += reliability_section(result.tables.get("reliability.csv"))
    blocks += end_of_study_section(context.end_of_study if context else None)
    for measure in result.measures:
        blocks += measure_section(measure)
    return typeset(blocks)


def method_section(result: AnalysisResult, options: AnalysisOptions) -> list[Block]:
    first = result.measures[0]
    within = first.within
    levels = "; ".join(f"{f}: {', '.join(str(v) for v in first.descriptives[f].drop_duplicates())}"
                       for f in within if f in first.descriptives) or ", ".join(within)
    design = (Paragraph(
        f"Design: {within[0]} between participants × {' × '.join(within[1:])} within participants (participant "
        f"column: {first.subject}); levels in the study's order ({levels}). Each measure was analysed with a mixed "
        f"(split-plot) ANOVA: {within[0]} against the participants-within-groups error term, every within effect "
        f"and its interaction with {within[0]} against the participant × effect error term within groups "
        f"({SS_TYPE_TEXT[options.ss_type]}; sphericity of the within part from the pooled within-group "
        f"covariance). Follow-ups: {within[0]} at each within cell (one-way between-participants ANOVA), each "
        f"within factor within each group of {within[0]} {FOLLOW_UP_TEXT[options.follow_up_error]}; Holm within "
        "each family. Participants without a value in every cell of a measure were left out of that measure "
        "(complete cases).")
        if options.between else Paragraph(
        f"Design: {' × '.join(within)}, all within participants (participant column: {first.subject}); "
        f"levels in the study's order ({levels}). Each measure was analysed with a repeated-measures "
        "ANOVA of every main effect and interaction, each tested against its own participant × effect "
        "error term (MSE in the table); participants without a value in every cell of a measure were "
        "left out of that measure (complete cases)."))
    return [
        Heading(2, "Method"),
        design,
        Paragraph("Which p to read: an effect with one degree of freedom is spherical, so its uncorrected test is "
                  "read. For an effect with more, Mauchly's test is reported but does not decide: the "
                  f"Greenhouse–Geisser corrected test is read when ε_GG ≤ {GG_THRESHOLD}, the Huynh–Feldt "
                  "corrected test (ε_HF capped at 1) otherwise (Huynh & Feldt, 1976; Girden, 1992). The sentences "
                  "below use the degrees of freedom and p of the test read; the table shows all of them."),
        *([] if options.between else [Paragraph(
            "Follow-ups: simple main effects of every factor at every combination of the other factors' levels "
            "(one-way repeated-measures ANOVAs with their own error term, Holm-adjusted within each factor); for "
            "factors with more than two levels, paired t tests between all pairs of levels on the participants' "
            "marginal means (Holm-adjusted within the factor), with the mean difference and its 95% CI and "
            "Cohen's d_z (mean difference / SD of the differences) with its exact 95% CI (noncentral t). Rating "
            "measures also get Wilcoxon signed-rank and Friedman tests.")]),
        Paragraph("Effect sizes: generalized eta squared η²G (Olejnik & Algina, 2003; Bakeman, 2005) with a 90% "
                  f"percentile bootstrap CI ({BOOTSTRAP_RESAMPLES} resamples of participants, seed {options.seed}), "
                  "and partial eta squared with a 90% CI from the noncentral F distribution (Steiger, 2004). "
                  "Error bars and cell CIs: within-subject 95% CIs (Cousineau, 2005; Morey, 2008). "
                  f"Computed with {_versions()}."),
    ]


def finished_section(finished: pd.DataFrame | None) -> list[Block]:
    if finished is None:
        return []
    rows = [(str(r.factor), str(r.at), str(r.test), str(int(r.n)), number(r.statistic, 2),
             "" if pd.isna(r.df) else str(int(r.df)), format_p(float(r.p)), str(r.note))
            for r in finished.itertuples()]
    return [Heading(2, "finished (every order delivered before the horizon)"),
            Paragraph("Paired binary outcome: McNemar's exact test for two conditions, Cochran's Q for more; "
                      "across all conditions and for each factor within each cell of the others."),
            table(("factor", "at", "test", "n", "statistic", "df", "p", "note"), rows)]


def reliability_section(reliability: pd.DataFrame | None) -> list[Block]:
    if reliability is None or reliability.empty:
        return []
    rows = [(str(r.scale), str(r.condition), str(int(r.n)), str(int(r.items)),
             format_proportion(float(r.alpha), 2), interval(r.ci95_low, r.ci95_high, True), str(r.note))
            for r in reliability.itertuples()]
    return [Heading(2, "Questionnaire scales"),
            Paragraph("Scale scores are the mean of their items after reverse-coded items are reversed "
                      "(max + min − value); reliability is Cronbach's α with Feldt's 95% CI, over all responses "
                      "and per condition."),
            table(("scale", "condition", "n", "items", "α", "95% CI", "note"), rows),
            BulletList(("α over all conditions pools several responses of each participant; compare the "
                        "per-condition values with published norms.",))]


def write_report(result: AnalysisResult, out_dir: Path, options: AnalysisOptions,
                 context: ReportContext | None = None) -> tuple[Path, Path]:
    """Write ``report.md`` and ``report.html`` into ``out_dir``; return their paths."""
    blocks = build_report(result, options, context)
    md, page = out_dir / "report.md", out_dir / "report.html"
    md.write_text(render_markdown(blocks), encoding="utf-8")
    page.write_text(render_html(blocks, options.title), encoding="utf-8")
    return md, page


def _versions() -> str:
    names = ("pingouin", "statsmodels", "pandas", "numpy", "scipy")
    return ", ".join(f"{name} {importlib.metadata.version(name)}" for name in names)
