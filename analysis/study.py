"""``analyze_study``: export a stored study, then run the repeated-measures analysis on its cells.

The export goes to ``<out>/data/`` (see :mod:`analysis.export`); ``cells.csv`` is read back from there and
handed to :func:`analysis.run.analyze_long` with ``within = (robot, kitchen)`` and ``subject =
participant``, so the statistics are exactly those of the exported file. The report gets a section listing
every participant left out of the analysis with the reason: flagged as a test run, excluded by the
experimenter, or missing a cell (per measure, the complete-case rule of :mod:`analysis.cells` applies too).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import pandas as pd
from sqlalchemy import Engine

from analysis.document import Block, BulletList, Heading, Paragraph, render_html, render_markdown
from analysis.errors import AnalysisInputError
from analysis.export import ExportResult, export_study
from analysis.report import TITLE, build_report
from analysis.results import AnalysisResult
from analysis.run import analyze_long

DEFAULT_MEASURES: tuple[str, ...] = (
    "kb_gap_mean", "kb_gap_ticks_pct", "interrupts", "interrupts_per_selection", "ticks", "robot_in_fov_pct")
WITHIN: tuple[str, str] = ("robot", "kitchen")
SUBJECT = "participant"
DATA_DIR = "data"


@dataclass(frozen=True, slots=True, eq=False)
class StudyAnalysis:
    export: ExportResult
    result: AnalysisResult
    cells: pd.DataFrame
    """``cells.csv`` as read back from the export (the analysis input)."""


def analyze_study(source: Engine | str, study_id: str, out_dir: Path | str,
                  measures: Sequence[str] = DEFAULT_MEASURES) -> StudyAnalysis:
    """Export ``study_id`` into ``<out_dir>/data`` and analyse ``measures`` into ``out_dir``."""
    out = Path(out_dir)
    export = export_study(source, study_id, out / DATA_DIR)
    cells = pd.read_csv(out / DATA_DIR / "cells.csv")
    if cells.empty:
        raise AnalysisInputError(
            f"study {study_id!r} has no analysable main trial (cells.csv is empty); "
            f"see {out / DATA_DIR / 'excluded.csv'} and participants.csv")
    result = analyze_long(cells, list(measures), list(WITHIN), SUBJECT, out)
    _write_report(result, export, study_id)
    return StudyAnalysis(export, result, cells)


def participants_section(export: ExportResult, study_id: str) -> list[Block]:
    """Who is in the store, who is in the cells, and every participant left out with the reason."""
    tables = export.dataset.tables
    people, excluded = tables["participants.csv"], tables["excluded.csv"]
    blocks: list[Block] = [
        Heading(2, "Participants"),
        Paragraph(
            f"Study {study_id}: {len(people)} participants in the store, "
            f"{int((people['cells'] > 0).sum())} with at least one cell in {DATA_DIR}/cells.csv, "
            f"{int(people['complete'].sum())} with a cell in every condition. "
            f"The exported files and their data dictionary are in {DATA_DIR}/."),
    ]
    if excluded.empty:
        blocks.append(Paragraph("No participant was left out."))
        return blocks
    blocks.append(Paragraph(f"Left out of the complete-case analysis ({DATA_DIR}/excluded.csv):"))
    blocks.append(BulletList(tuple(
        f"participant {row.participant} ({row.category}): {row.reason}" for row in excluded.itertuples())))
    return blocks


def _write_report(result: AnalysisResult, export: ExportResult, study_id: str) -> None:
    blocks = build_report(result.measures)
    first_measure = next((i for i, b in enumerate(blocks) if isinstance(b, Heading) and b.level == 2),
                         len(blocks))
    blocks[first_measure:first_measure] = participants_section(export, study_id)
    (result.out_dir / "report.md").write_text(render_markdown(blocks), encoding="utf-8")
    (result.out_dir / "report.html").write_text(render_html(blocks, TITLE), encoding="utf-8")
