"""``analyze_long``: the whole statistics pipeline for a long table, written to one folder.

The table has one row per participant (``subject``) and cell of the within design (one to three factors); with
``options.between`` a column names each participant's group and the analysis is the mixed ANOVA
(:mod:`analysis.pipeline.mixed_run`).
In order: levels put in the study's order (:mod:`analysis.preparation.levels`), questionnaire scales scored
(:mod:`analysis.measures.scale_scores`), rows excluded by rule set aside with their reasons
(:mod:`analysis.preparation.exclusions`), the censoring of ``ticks`` and the analysis of ``finished``
(:mod:`analysis.statistics.censoring`), scale reliability, then each measure (:mod:`analysis.pipeline.measure_run`), its
plots, the CSV files and the report.

Files written into ``out_dir``::

    anova.csv           measure, the columns of analysis.statistics.anova.ANOVA_COLUMNS, ges_ci_low, ges_ci_high
    simple_effects.csv  measure, the columns of analysis.followups.simple_effects.SIMPLE_EFFECT_COLUMNS
    pairwise.csv        measure, the columns of analysis.followups.pairwise.PAIRWISE_COLUMNS
    rank_tests.csv      measure, the columns of analysis.statistics.nonparametric.RANK_TEST_COLUMNS (rating measures)
    descriptives.csv    measure, <within factors>, n, mean, sd, se_ws, ci95_low, ci95_high
    excluded.csv        measure, subject, reason (the complete-case rule)
    exclusions.csv      subject, cell, rule, reason, included (rows left out by rule)
    normality.csv       measure, n_residuals, W, p, note
    order.csv           measure and the order check (analysis.statistics.order_check.ORDER_COLUMNS)
    censoring.csv       cell, n, reached_horizon, share           (when the table has ``finished``)
    finished.csv        factor, at, test, n, statistic, df, p, note (when the table has ``finished``)
    reliability.csv     scale, condition, n, items, alpha, ci95_low, ci95_high, note (when scales are declared)
    lmm.csv             the linear mixed model per measure (``options.lmm``;
                        analysis.statistics.lmm_count_models.MODEL_COLUMNS)
    count_model.csv     the Poisson GEE of the interrupts (when they are analysed; analysis.statistics.lmm_count_models)
    plots/<measure>_interaction.png|.svg, plots/<measure>_paired.png|.svg
    report.md, report.html

A measure that cannot be tested is reported as such with the reason; every other measure still runs, and the
run's ``warnings`` list each such case.
"""

from __future__ import annotations

import re
import zlib
from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path

import numpy as np
import pandas as pd

from analysis.measures.scale_scores import score_scales
from analysis.pipeline.measure_run import analyze_measure, unreadable_measure
from analysis.pipeline.mixed_run import analyze_mixed_measure
from analysis.preparation.cells import non_finite_values, non_numeric_values, require_columns, validate_design
from analysis.preparation.exclusions import RULES, apply_exclusions, missing_reasons
from analysis.preparation.levels import apply_level_order
from analysis.preparation.measure_info import measure_info
from analysis.preparation.options import AnalysisOptions
from analysis.reporting.analysis_report import write_report
from analysis.reporting.plots import interaction_plot, paired_plot
from analysis.reporting.quality_section import ReportContext
from analysis.source.input_errors import AnalysisInputError
from analysis.statistics.censoring import censoring_table, finished_tests
from analysis.statistics.lmm_count_models import COUNT_MEASURES, MODEL_COLUMNS, count_tests, lmm_tests, model_sentence
from analysis.statistics.normality import NORMALITY_COLUMNS
from analysis.statistics.order_check import ORDER_COLUMNS
from analysis.statistics.reliability import scale_reliability
from analysis.statistics.results import AnalysisResult, MeasureResult

MAX_FACTORS = 3
PER_MEASURE = ("anova", "simple_effects", "pairwise", "rank_tests", "descriptives", "excluded")


def analyze_long(df: pd.DataFrame, measures: Sequence[str], within: Sequence[str], subject: str,
                 out_dir: Path | str, options: AnalysisOptions | None = None,
                 context: ReportContext | None = None) -> AnalysisResult:
    """Analyse each of ``measures`` in the long table ``df`` and write the results to ``out_dir``.

    Raises ``AnalysisInputError`` (nothing written) for a missing or non-numeric column, a malformed design (a
    factor with one level, two rows for one participant and cell) or a level order that does not fit.
    """
    options = options or AnalysisOptions()
    within = _check_arguments(df, measures, within, subject, options)
    ordered = (*within, options.between) if options.between else within
    table = apply_level_order(df, ordered, options.levels, options.strict_levels)
    if options.between:
        check_between(table, options.between, subject)
    table = score_scales(table, options.items, options.scales) if options.scales else table
    infinite = [text for m in measures if (text := non_finite_values(table, m, within, subject))]
    if infinite:
        raise AnalysisInputError("; ".join(infinite) + ". A cell holds a number or is empty (a missing value): "
                                 "correct the file or empty those cells")
    unreadable = {m: non_numeric_values(table, m, within, subject) for m in measures}
    for measure in measures:
        validate_design(table.assign(**{measure: pd.to_numeric(table[measure], errors="coerce")})
                        if unreadable[measure] else table, measure, within, subject)
    kept, exclusions = apply_exclusions(table, within, subject, options.include)
    if kept.empty:
        raise AnalysisInputError(_all_excluded(exclusions, len(table)))
    has_finished = options.finished in kept.columns
    censoring = censoring_table(kept, within, options.finished) if has_finished else None
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    results: list[MeasureResult] = []
    files: list[Path] = []
    model_rows: dict[str, list[dict[str, object]]] = {"lmm.csv": [], "count_model.csv": []}
    for measure, stem in zip(measures, _file_stems(measures), strict=True):
        if unreadable[measure]:
            results.append(unreadable_measure(kept, measure, within, subject, unreadable[measure]))
            continue
        info = measure_info(measure, kept[measure], options.horizon, options.ratings)
        if options.between:
            result, clean = analyze_mixed_measure(kept, measure, within, options.between, subject, info, options,
                                                  missing_reasons(exclusions), censoring)
        else:
            result, clean = analyze_measure(kept, measure, within, subject, info, options,
                                            missing_reasons(exclusions), censoring)
        if result.testable and options.plots and len(result.within) <= MAX_FACTORS:
            result, written = _plots(result, clean, out, stem, options.seed, mixed=bool(options.between))
            files += written
        results.append(_with_models(result, kept, measure, within, subject, options, model_rows))
    tables = {
        **{f"{name}.csv": _stack(results, name) for name in PER_MEASURE},
        "exclusions.csv": exclusions,
        "normality.csv": pd.DataFrame([{"measure": r.measure, "n_residuals": r.normality.n_residuals,
                                        "W": r.normality.w, "p": r.normality.p, "note": r.normality.note}
                                       for r in results], columns=NORMALITY_COLUMNS),
        "order.csv": pd.DataFrame([r.order.row() for r in results], columns=ORDER_COLUMNS),
    }
    if censoring is not None:
        tables["censoring.csv"] = censoring
        tables["finished.csv"] = finished_tests(kept, within, subject, options.finished)
    tables.update({name: pd.DataFrame(rows, columns=MODEL_COLUMNS) for name, rows in model_rows.items() if rows})
    if options.scales:
        tables["reliability.csv"] = scale_reliability(kept, options.items, options.scales, within)
    for name, frame in tables.items():
        frame.to_csv(out / name, index=False)
        files.append(out / name)
    warnings = tuple(f"{r.measure}: {note}" for r in results for note in r.notes if "not testable" in note)
    checked = tuple(rule.name for rule in RULES if rule.column in df.columns)
    formulas = tuple(dict.fromkeys(str(r["formula"]) for r in model_rows["lmm.csv"]))
    analysis = AnalysisResult(tuple(results), tables, warnings, out, (), checked, formulas)
    files += write_report(analysis, out, options, context)
    return replace(analysis, files=tuple(files))


def _with_models(result: MeasureResult, kept: pd.DataFrame, measure: str, within: Sequence[str], subject: str,
                 options: AnalysisOptions, model_rows: dict[str, list[dict[str, object]]]) -> MeasureResult:
    """``result`` with the models beside the ANOVA (:mod:`analysis.statistics.lmm_count_models`) in its notes; their
    rows added to ``model_rows``."""
    if not pd.api.types.is_numeric_dtype(kept[measure]):
        return result
    factors = [options.between, *within] if options.between else list(within)
    notes = list(result.notes)
    for name, wanted, fit in (("lmm.csv", options.lmm, lmm_tests),
                              ("count_model.csv", measure in COUNT_MEASURES, count_tests)):
        if not wanted:
            continue
        rows = fit(kept, measure, factors, subject)
        model_rows[name] += rows
        frame = pd.DataFrame(rows, columns=MODEL_COLUMNS)
        notes.append(f"{frame['model'].iloc[0]}, {frame['formula'].iloc[0]} ({name}): "
                     + "; ".join(model_sentence(r) for _, r in frame.iterrows()))
    return replace(result, notes=tuple(notes))


def _plots(result: MeasureResult, clean: pd.DataFrame, out: Path, stem: str, seed: int, mixed: bool = False
           ) -> tuple[MeasureResult, list[Path]]:
    plot_dir = out / "plots"
    paths, clipped = interaction_plot(result.descriptives, result.info, result.within,
                                      plot_dir / f"{stem}_interaction")
    rng = np.random.default_rng([seed, zlib.crc32(result.measure.encode()), 1])
    if not mixed:
        paths += paired_plot(clean, result.info, result.within, result.subject, plot_dir / f"{stem}_paired", rng)
    notes = result.notes
    if clipped:
        notes += (f"error bars of the interaction plot are cut at the natural bounds of {result.measure} "
                  f"({_bounds(result.info.lower, result.info.upper)}); the CIs in the table are not",)
    return replace(result, notes=notes, plots=tuple(p.relative_to(out).as_posix() for p in paths)), paths


def _check_arguments(df: pd.DataFrame, measures: Sequence[str], within: Sequence[str], subject: str,
                     options: AnalysisOptions) -> tuple[str, ...]:
    if isinstance(measures, str):
        raise AnalysisInputError(f"measures must be a list of column names, got the string {measures!r}")
    if not measures:
        raise AnalysisInputError("no measure given")
    if df.empty:
        raise AnalysisInputError("the table has no rows (a header only): nothing to analyse")
    if len(set(measures)) != len(measures):
        raise AnalysisInputError(f"a measure is named twice: {list(measures)}")
    if not 1 <= len(within) <= MAX_FACTORS or len(set(within)) != len(within):
        raise AnalysisInputError(f"the analysis takes one to {MAX_FACTORS} distinct within factors, got "
                                 f"{list(within)}")
    scale_columns = {s.column for s in options.scales}
    between = [options.between] if options.between else []
    require_columns(df, [*within, subject, *between, *(m for m in measures if m not in scale_columns)])
    if options.between in (*within, subject):
        raise AnalysisInputError(f"the between factor {options.between!r} is also a within factor or the subject")
    return tuple(within)


def _all_excluded(exclusions: pd.DataFrame, rows: int) -> str:
    """The message when the exclusion rules leave no row: how many each rule took, and the option that keeps them."""
    taken = exclusions[exclusions["included"] == 0].groupby("rule", sort=False).size()
    by_rule = {rule.name: rule for rule in RULES}
    parts = [f"{count} by rule {name} ({by_rule[name].label}s; kept with {by_rule[name].option})"
             for name, count in taken.items()]
    return (f"all {rows} row(s) were left out by the exclusion rules: " + ", ".join(parts)
            + "; nothing is left to analyse (the rows are listed either way with the option)")


def check_between(table: pd.DataFrame, between: str, subject: str) -> None:
    """A between factor has a level in every row, one level per participant, and at least two levels."""
    empty = int(table[between].isna().sum())
    if empty:
        raise AnalysisInputError(f"column {between!r} has {empty} empty value(s); every row needs a group")
    per_subject = table.groupby(subject, observed=True)[between].nunique()
    if (per_subject > 1).any():
        who = per_subject[per_subject > 1].index[0]
        raise AnalysisInputError(f"subject {who} has more than one level of the between factor {between!r}; "
                                 "a between factor has one level per participant")
    if table[between].nunique() < 2:
        raise AnalysisInputError(f"the between factor {between!r} has fewer than two levels")


def _file_stems(measures: Sequence[str]) -> list[str]:
    """File-name-safe stems; a clash after sanitising gets a numeric suffix."""
    stems: list[str] = []
    for measure in measures:
        stem = re.sub(r"[^A-Za-z0-9_.-]+", "_", measure).strip("._") or "measure"
        candidate, k = stem, 2
        while candidate in stems:
            candidate, k = f"{stem}_{k}", k + 1
        stems.append(candidate)
    return stems


def _stack(results: list[MeasureResult], attribute: str) -> pd.DataFrame:
    frames = [getattr(r, attribute) for r in results]
    columns = ["measure", *next((list(f.columns) for f in frames), [])]
    non_empty = [f.assign(measure=r.measure) for r, f in zip(results, frames, strict=True) if not f.empty]
    if not non_empty:
        return pd.DataFrame(columns=columns)
    return pd.concat(non_empty, ignore_index=True)[columns]


def _bounds(lower: float, upper: float) -> str:
    return f"{lower:g} to {upper:g}"
