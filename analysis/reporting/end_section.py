"""The report's section on the questionnaire at the end of the study and on the free-text answers
(:mod:`analysis.statistics.end_of_study`)."""

from __future__ import annotations

from typing import Any

import pandas as pd

from analysis.reporting.document import Block, BulletList, Heading, Paragraph, table
from analysis.reporting.report_tables import interval, number
from analysis.statistics.apa import format_proportion
from analysis.statistics.end_of_study import END_FILE, EndOfStudy


def end_of_study_section(summary: EndOfStudy | None) -> list[Block]:
    if summary is None:
        return []
    blocks: list[Block] = [Heading(2, "Questionnaires at the end of the study, and free text")]
    rated = summary.table[summary.table["kind"].isin(["rating", "scale"])]
    if not rated.empty:
        blocks += [
            Paragraph(f"Answered once by each participant: descriptives over the {summary.participants} "
                      "participants with cells (wide.csv), and per group of a factor between participants. A scale "
                      "score is the mean of its items after reverse-coded items are reversed; its Cronbach's α "
                      "(Feldt's 95% CI) is the textbook one, one response per participant. Also in "
                      f"{END_FILE}."),
            table(("question", "group", "n", "mean", "sd", "median", "range", "α [95% CI]"), [
                (str(r.question), str(r.group), str(int(r.n)), number(r.mean), number(r.sd), number(r.median),
                 _range(r.min, r.max), _alpha(r)) for r in rated.itertuples()])]
        notes = [f"{r.question} ({r.group}): {r.note}" for r in rated.itertuples()
                 if r.kind == "scale" and isinstance(r.note, str) and r.note]
        if notes:
            blocks.append(BulletList(tuple(notes)))
    chosen = summary.table[summary.table["kind"] == "choice"]
    if not chosen.empty:
        blocks += [Paragraph("Choice items: how many participants chose each option."),
                   table(("question", "group", "option", "chosen", "of", "share"), [
                       (str(r.question), str(r.group), str(r.option), str(int(r.count)), str(int(r.n)),
                        format_proportion(r.count / r.n, 2) if r.n else "n/a") for r in chosen.itertuples()])]
    if summary.free_text:
        blocks += [Paragraph(f"Free-text answers are not analysed; they are in {summary.answers_file} (column text, "
                             "one row per answer, with the participant and the trial it followed; participants "
                             "flagged as test runs or excluded not counted here):"),
                   BulletList(summary.free_text)]
    return blocks


def _range(low: object, high: object) -> str:
    return "" if pd.isna(low) else f"{float(low):g}–{float(high):g}"  # type: ignore[arg-type]


def _alpha(row: Any) -> str:
    if row.kind != "scale" or pd.isna(row.alpha):
        return ""
    return f"{format_proportion(float(row.alpha), 2)} {interval(row.alpha_ci_low, row.alpha_ci_high, True)}"
