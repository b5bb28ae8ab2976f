"""``analyze_study``: export a stored study, then run the repeated-measures analysis on its cells.

The export goes to ``<out>/data/`` (see :mod:`analysis.exports.study_export`); ``cells.csv`` is read back from there, so
the statistics are exactly those of the exported file. The design comes from the configuration stored with the
study (:mod:`analysis.source.study_design`): the within factors of ``factors`` that have two or more levels, their
levels in the study's order, the horizon (``ticks``' bound), the rating items and the scales, which are scored
and analysed by default beside :data:`DEFAULT_MEASURES`. Each cell carries its trial's ``invalid_reason`` and
``missed_decisions_pct`` from ``trials.csv`` when the export records them, so invalid trials are left out and
listed (:mod:`analysis.preparation.exclusions`). The report's data-quality section lists everyone the export left out
(test runs, exclusions by the experimenter, missing cells with why each is missing) and every invalid trial.
"""

from __future__ import annotations

from collections.abc import Collection, Sequence
from dataclasses import dataclass, replace
from pathlib import Path

import pandas as pd
from sqlalchemy import Engine

from analysis.exports.study_export import ExportResult, export_study
from analysis.pipeline.analyze_long import analyze_long
from analysis.preparation.exclusions import INVALID, LOW_ENGAGEMENT
from analysis.preparation.options import POOLED, AnalysisOptions
from analysis.reporting.quality_section import ReportContext
from analysis.source.input_errors import AnalysisInputError
from analysis.source.study_design import StudyDesign
from analysis.statistics.end_of_study import END_FILE, end_of_study
from analysis.statistics.results import AnalysisResult

DEFAULT_MEASURES: tuple[str, ...] = (
    "kb_diff_freq", "kb_diff_avg", "interrupts", "interrupts_per_selection", "ticks", "robot_in_fov_pct",
    "kb_gap_mean", "kb_gap_ticks_pct")
"""The paper's H1 (KB gap: ``kb_diff_freq``, ``kb_diff_avg``, as its code measures it) and H2 (interrupts) first;
our older status gap last, as a secondary measure."""
SUBJECT = "participant"
PILOT = "pilot"
"""The ``include`` name that keeps simulated pilot participants (``--include-pilot``)."""
DATA_DIR = "data"
TRIAL_COLUMNS = (INVALID.column, INVALID.detail_column, LOW_ENGAGEMENT.column, LOW_ENGAGEMENT.detail_column)
"""Columns of ``trials.csv`` the exclusion rules read, joined onto the cells by ``trial_id``."""


@dataclass(frozen=True, slots=True, eq=False)
class StudyAnalysis:
    export: ExportResult
    result: AnalysisResult
    cells: pd.DataFrame
    """``cells.csv`` as read back from the export (the analysis input)."""
    design: StudyDesign


def analyze_study(source: Engine | str, study_id: str, out_dir: Path | str, measures: Sequence[str] | None = None,
                  include: Collection[str] = (), seed: int = 0, plots: bool = True, lmm: bool = False,
                  ss_type: int = 3, follow_up_error: str = POOLED) -> StudyAnalysis:
    """Export ``study_id`` into ``<out_dir>/data`` and analyse ``measures`` (default: :data:`DEFAULT_MEASURES`
    and the study's scales) into ``out_dir``; ``include`` names exclusion rules whose rows are kept (with
    ``invalid`` the export itself keeps invalid trials in ``cells.csv``: ``export_study(include_invalid=True)``;
    without it they are left out there and listed in ``excluded.csv``), and ``"pilot"`` in it keeps simulated
    pilot participants (left out of the export otherwise). ``ss_type`` and ``follow_up_error``: the mixed design's
    conventions (:class:`analysis.preparation.options.AnalysisOptions`)."""
    out = Path(out_dir)
    export = export_study(source, study_id, out / DATA_DIR,
                          include_invalid=INVALID.name in include or LOW_ENGAGEMENT.name in include,
                          include_pilot=PILOT in include)
    cells = read_cells(out)
    trials = pd.read_csv(out / DATA_DIR / "trials.csv", dtype={SUBJECT: str})
    if cells.empty:
        raise AnalysisInputError(f"study {study_id!r} has no analysable main trial (cells.csv is empty); "
                                 + _why_empty(export, out / DATA_DIR))
    design = StudyDesign.from_config(export.dataset.config)
    within, between = varied_factors(cells, design)
    if len(between) > 1:
        raise AnalysisInputError(f"study {study_id!r} has {len(between)} between factors ({', '.join(between)}); "
                                 "the analysis takes one")
    if not within:
        raise AnalysisInputError(f"study {study_id!r} has no within factor with two levels in its cells "
                                 f"(factors {list(design.factors) or 'none'}; see {out / DATA_DIR / 'cells.csv'})")
    ratings = {i.column: (float(i.minimum), float(i.maximum)) for i in design.items}
    ratings.update({s.column: _scale_range(s.items, ratings) for s in design.scales})
    options = AnalysisOptions(
        levels=design.levels, strict_levels=False, ratings=ratings, items=design.items, scales=design.scales,
        include=frozenset(include), horizon=design.horizon, seed=seed, plots=plots, lmm=lmm, ss_type=ss_type,
        follow_up_error=follow_up_error,
        title=f"{'Mixed' if between else 'Repeated-measures'} analysis: study {study_id}",
        between=between[0] if between else None)
    chosen = list(measures) if measures is not None else [*DEFAULT_MEASURES, *(s.column for s in design.scales)]
    context = _context(export, trials, study_id, design, within)
    result = analyze_long(attach_trial_columns(cells, trials), chosen, within, SUBJECT, out, options, context)
    if context.end_of_study is not None:
        path = out / END_FILE
        context.end_of_study.table.to_csv(path, index=False)
        result = replace(result, files=(*result.files, path))
    return StudyAnalysis(export, result, cells, design)


def _why_empty(export: ExportResult, folder: Path) -> str:
    """What to do about an export without cells: run the pilots that are stored, keep the invalid trials, or look
    at who is listed where."""
    hints = []
    if export.dataset.pilots_left_out:
        hints.append(f"the store holds {export.dataset.pilots_left_out} simulated pilot participant(s) of this "
                     "study (steakhouse pilot), which are left out unless --include-pilot: add --include-pilot to "
                     "analyse them")
    invalid = export.dataset.excluded["category"].isin(["invalid", "low_engagement"]).sum()
    if invalid:
        hints.append(f"{invalid} participant(s) lost their cells to invalid or low-engagement trials: "
                     "--include-invalid keeps those trials")
    if export.dataset.tables["participants.csv"].empty and not hints:
        hints.append("no participant has joined it yet")
    return "; ".join([*hints, f"see {folder / 'excluded.csv'} and participants.csv"])


def read_cells(out: Path) -> pd.DataFrame:
    """The exported ``cells.csv`` under ``out``. Levels are read as written: an angle's level is ``90`` (as in the
    design), not the float ``90.0``."""
    return pd.read_csv(out / DATA_DIR / "cells.csv", dtype={SUBJECT: str, "fov_angle": str})


def varied_factors(cells: pd.DataFrame, design: StudyDesign) -> tuple[list[str], list[str]]:
    """The design's factors within and between participants that take two levels or more in ``cells``."""
    def varied(factors: Sequence[str]) -> list[str]:
        return [f for f in factors if f in cells.columns and cells[f].nunique() > 1]
    return varied(design.factors), varied(design.between)


def attach_trial_columns(cells: pd.DataFrame, trials: pd.DataFrame) -> pd.DataFrame:
    """``cells`` with the rule columns of their trial (:data:`TRIAL_COLUMNS`) that ``trials`` has and ``cells``
    lacks, joined on ``trial_id``."""
    columns = [c for c in TRIAL_COLUMNS if c in trials.columns and c not in cells.columns]
    if not columns or "trial_id" not in cells.columns:
        return cells
    return cells.merge(trials[["trial_id", *columns]], on="trial_id", how="left")


def _context(export: ExportResult, trials: pd.DataFrame, study_id: str, design: StudyDesign,
             within: list[str]) -> ReportContext:
    people = export.dataset.tables["participants.csv"]
    excluded = export.dataset.tables["excluded.csv"]
    single = list(design.single_level) + [f for f in design.factors if f not in within]
    summary = (f"Study {study_id}: {len(people)} participants in the store, {int((people['cells'] > 0).sum())} "
               f"with at least one cell in {DATA_DIR}/cells.csv, {int(people['complete'].sum())} with a cell in "
               f"every condition. Within factors: {', '.join(within)}"
               + (f" ({', '.join(single)} has a single level here and is not a factor)" if single else "")
               + f". The exported files and their data dictionary are in {DATA_DIR}/.")
    left_out = tuple(f"participant {r.participant} ({r.category}): {r.reason}" for r in excluded.itertuples())
    invalid: tuple[str, ...] | None = None
    if INVALID.column in trials.columns:
        marked = trials[(trials["kind"] == "main") & trials[INVALID.column].notna()
                        & (trials[INVALID.column].astype(str).str.strip() != "")]
        invalid = tuple(f"participant {r.participant}, main trial {int(r.index) + 1} ({r.condition}, attempt "
                        f"{int(r.attempt)}): {getattr(r, INVALID.column)}" for r in marked.itertuples())
    tables = export.dataset.tables
    end = end_of_study(tables["wide.csv"], tables["answers.csv"], export.dataset.config, export.dataset.design.between,
                       f"{DATA_DIR}/answers.csv")
    return ReportContext(summary, left_out, invalid, low_engagement_lines(trials), end)


def low_engagement_lines(trials: pd.DataFrame) -> tuple[str, ...] | None:
    """One line per low-engagement main trial of ``trials.csv`` (``None``: the export does not record it)."""
    if LOW_ENGAGEMENT.column not in trials.columns:
        return None
    reasons = trials[LOW_ENGAGEMENT.column]
    marked = trials[(trials["kind"] == "main") & reasons.notna() & (reasons.astype(str).str.strip() != "")]
    return tuple(f"participant {r.participant}, main trial {int(r.index) + 1} ({r.condition}, attempt "
                 f"{int(r.attempt)}): {getattr(r, LOW_ENGAGEMENT.column)}" for r in marked.itertuples())


def _scale_range(columns: Sequence[str], ratings: dict[str, tuple[float, float]]) -> tuple[float, float]:
    bounds = [ratings[c] for c in columns if c in ratings]
    if not bounds:
        return (float("-inf"), float("inf"))
    return (min(b[0] for b in bounds), max(b[1] for b in bounds))
