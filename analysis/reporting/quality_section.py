"""The report's first section, "Data quality": who is in the analysis and who was left out and why, trials the
server marked invalid, censored cells, the order check and residual normality, and every test that could not be
computed."""

from __future__ import annotations

from dataclasses import dataclass

import pandas as pd

from analysis.preparation.exclusions import INVALID, LOW_ENGAGEMENT
from analysis.reporting.document import Block, BulletList, Heading, Paragraph, table
from analysis.reporting.measure_section import normality_line
from analysis.statistics.apa import format_proportion
from analysis.statistics.censoring import CENSORED_MEASURES
from analysis.statistics.end_of_study import EndOfStudy
from analysis.statistics.results import AnalysisResult


@dataclass(frozen=True, slots=True)
class ReportContext:
    """What the table alone does not say, given by the caller (a stored study's export)."""

    summary: str = ""
    """One sentence on the participants of the study."""
    left_out: tuple[str, ...] = ()
    """Participants the export left out of the cells, with the reason."""
    invalid_trials: tuple[str, ...] | None = None
    """Main trials the server marked invalid (``None``: the export does not record robot health)."""
    low_engagement_trials: tuple[str, ...] | None = None
    """Main trials the server marked low-engagement (``None``: the export does not record engagement)."""
    end_of_study: EndOfStudy | None = None
    """The end-of-study questionnaire's answers and where the free text is (a stored study's export)."""


def quality_section(result: AnalysisResult, context: ReportContext | None) -> list[Block]:
    context = context or ReportContext()
    blocks: list[Block] = [Heading(2, "Data quality")]
    if context.summary:
        blocks.append(Paragraph(context.summary))
    blocks.append(table(("measure", "n used", "of", "left out (complete cases)"), [
        (r.measure, str(r.n_used), str(r.n_total), str(len(r.excluded))) for r in result.measures]))
    blocks += _left_out(result, context)
    blocks += _invalid(result, context)
    blocks += _low_engagement(result, context)
    blocks += _censoring(result)
    blocks += [Heading(3, "Order and carry-over"), BulletList(tuple(r.order.sentence for r in result.measures))]
    blocks += [Heading(3, "Residual normality (Shapiro–Wilk on the ANOVA residuals)"),
               BulletList(tuple(normality_line(r) for r in result.measures))]
    if result.warnings:
        blocks += [Heading(3, "Not testable"), BulletList(result.warnings)]
    return blocks


def _left_out(result: AnalysisResult, context: ReportContext) -> list[Block]:
    rules = result.tables["exclusions.csv"]
    lines = list(context.left_out)
    lines += [f"participant {r.subject}, {r.cell}: {r.reason}" + (" (kept on request)" if r.included else "")
              for r in rules.itertuples()]
    by_reason: dict[tuple[str, str], list[str]] = {}
    for r in result.measures:
        for x in r.excluded.itertuples():
            by_reason.setdefault((str(x.subject), str(x.reason)), []).append(r.measure)
    lines += [f"participant {who}, left out of {', '.join(measures)}: {reason}"
              for (who, reason), measures in by_reason.items()]
    blocks: list[Block] = [Heading(3, "Left out, and why")]
    blocks.append(BulletList(tuple(lines)) if lines else Paragraph("Nobody was left out."))
    return blocks


def _invalid(result: AnalysisResult, context: ReportContext) -> list[Block]:
    blocks: list[Block] = [Heading(3, "Invalid robot trials")]
    marked = result.tables["exclusions.csv"]
    marked = marked[marked["rule"] == INVALID.name]
    if context.invalid_trials is not None:
        lines = context.invalid_trials
    elif INVALID.name in result.checked_rules:
        lines = tuple(f"participant {r.subject}, {r.cell}: {r.reason}" for r in marked.itertuples())
    else:
        return [*blocks, Paragraph(f"The table has no {INVALID.column} column: robot health was not recorded for "
                                   "these trials, so none could be left out for it.")]
    kept = "kept (--include-invalid)" if marked["included"].astype(bool).any() else "left out of the analysis"
    blocks.append(BulletList(tuple(lines)) if lines else Paragraph("No trial was marked invalid."))
    if lines:
        blocks.append(Paragraph(f"Invalid trials are {kept}."))
    return blocks


def _low_engagement(result: AnalysisResult, context: ReportContext) -> list[Block]:
    """One line: how many main trials were played without the participant taking part, and where they went."""
    marked = result.tables["exclusions.csv"]
    marked = marked[marked["rule"] == LOW_ENGAGEMENT.name]
    lines = context.low_engagement_trials
    if lines is None:
        lines = tuple(f"participant {r.subject}, {r.cell}: {r.reason}" for r in marked.itertuples())
    if not lines:
        return [Paragraph("No main trial was low-engagement (every participant took part in every round).")]
    kept = "kept (--include-invalid)" if marked["included"].astype(bool).any() else "left out of the analysis"
    return [Paragraph(f"{len(lines)} main trial(s) were low-engagement (played without the participant taking "
                      f"part) and are {kept}:"), BulletList(tuple(lines))]


def _censoring(result: AnalysisResult) -> list[Block]:
    blocks: list[Block] = [Heading(3, "Trials that reached the horizon")]
    censoring = result.tables.get("censoring.csv")
    if censoring is None:
        return [*blocks, Paragraph("The table has no finished column: censoring was not checked.")]
    blocks.append(table(("cell", "trials", "reached the horizon", "share"), [
        (str(r.cell), str(int(r.n)), str(int(r.reached_horizon)), "n/a" if pd.isna(r.share) else
         format_proportion(float(r.share), 2)) for r in censoring.itertuples()]))
    censored = int((censoring["reached_horizon"] > 0).sum())
    capped = [r.measure for r in result.measures if r.measure in CENSORED_MEASURES]
    names = " and ".join(capped)
    if not censored:
        blocks.append(Paragraph("Every trial finished before the horizon" + (f": {names} is not censored."
                                                                             if capped else ".")))
    elif capped:
        blocks.append(Paragraph(
            f"{censored} cell(s) have trials that reached the horizon; in those trials {names} "
            f"{'is' if len(capped) == 1 else 'are'} the horizon, not the time needed (see the note under {names} "
            "and the analysis of finished)."))
    else:
        blocks.append(Paragraph(
            f"{censored} cell(s) have trials that reached the horizon. No measure analysed here is capped by it "
            f"({', '.join(CENSORED_MEASURES)} would be), but those trials stopped before every order was "
            "delivered: read the analysis of finished beside the measures."))
    return blocks
