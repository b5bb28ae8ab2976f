"""The statistics of one measure: complete cases, the ANOVA with sphericity and effect-size intervals, follow-ups,
rank tests for ratings, descriptives, residual normality and the order check.

Nothing here raises for data a study can produce: a measure with fewer than two complete participants gets
empty tables and a note; a test that cannot be computed is a row with NaN statistics and a note (see
:mod:`analysis.statistics.anova`). Malformed input (a missing or non-numeric column) is refused earlier, in
:mod:`analysis.pipeline.analyze_long`.
"""

from __future__ import annotations

import zlib
from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd

from analysis.followups.pairwise import PAIRWISE_COLUMNS, pairwise_comparisons
from analysis.followups.simple_effects import SIMPLE_EFFECT_COLUMNS, simple_effects
from analysis.preparation.cells import complete_cases, factor_levels, wide_matrix
from analysis.preparation.measure_info import MeasureInfo
from analysis.preparation.options import AnalysisOptions
from analysis.statistics.anova import ANOVA_COLUMNS, anova_table, effect_name, effects_of, ges_bootstrap
from analysis.statistics.censoring import censoring_note
from analysis.statistics.descriptives import DESCRIPTIVE_STATS, cell_descriptives
from analysis.statistics.nonparametric import RANK_TEST_COLUMNS, rank_tests
from analysis.statistics.normality import Normality, residual_normality
from analysis.statistics.order_check import OrderCheck, order_check
from analysis.statistics.results import MeasureResult

MIN_SUBJECTS = 2
ANOVA_RESULT_COLUMNS = [*ANOVA_COLUMNS, "ges_ci_low", "ges_ci_high"]


def analyze_measure(df: pd.DataFrame, measure: str, within: Sequence[str], subject: str, info: MeasureInfo,
                    options: AnalysisOptions, why_missing: Mapping[tuple[object, str], str],
                    censoring: pd.DataFrame | None) -> tuple[MeasureResult, pd.DataFrame]:
    """The result for ``measure`` and the complete-case table it was computed from."""
    within = tuple(within)
    clean, excluded = complete_cases(df, measure, within, subject, why_missing)
    n_used = int(clean[subject].nunique())
    notes = [censoring_note(censoring, measure)] if censoring is not None else []
    base = {"measure": measure, "within": within, "subject": subject, "info": info, "n_used": n_used,
            "n_total": int(df[subject].nunique()), "excluded": excluded}
    constant = clean[measure].nunique() == 1
    levels = levels_of(clean, within)
    one_level = any(n < 2 for n in levels)
    if n_used < MIN_SUBJECTS or constant or one_level:
        reason = (f"not testable: every value is {clean[measure].iloc[0]:g}, nothing varies" if constant and
                  n_used >= MIN_SUBJECTS else
                  f"not testable: {n_used} participant(s) have a value in every cell of {' × '.join(within)}; "
                  f"at least {MIN_SUBJECTS} are needed")
        empty = MeasureResult(
            **base, anova=untestable_rows(within, levels_of(df, within), n_used, reason),
            simple_effects=_empty(SIMPLE_EFFECT_COLUMNS), pairwise=_empty(PAIRWISE_COLUMNS),
            rank_tests=_empty(RANK_TEST_COLUMNS),
            descriptives=cell_descriptives(clean, measure, within, subject) if n_used >= MIN_SUBJECTS and not one_level
            else _empty([*within, *DESCRIPTIVE_STATS]),
            normality=Normality(0, note=reason),
            order=OrderCheck(measure, n_used, 0, note=reason), notes=(reason, *filter(None, notes)), tested=False)
        return empty, clean
    values, _ = wide_matrix(clean, measure, within, subject)
    anova = anova_table(values, levels, within)
    rng = np.random.default_rng([options.seed, zlib.crc32(measure.encode())])
    intervals = ges_bootstrap(values, levels, within, rng)
    anova["ges_ci_low"] = [low for low, _ in intervals]
    anova["ges_ci_high"] = [high for _, high in intervals]
    simple = simple_effects(clean, measure, within, subject)
    pairwise = pairwise_comparisons(clean, measure, within, subject)
    notes += [f"{row.effect}: {row.note}" for row in anova.itertuples() if row.note]
    notes += [f"simple effect of {row.factor} at {row.at}: {row.note}" for row in simple.itertuples() if row.note]
    notes += [f"{row.level_1} vs {row.level_2}{f' at {row.at}' if row.at else ''}: {row.note}"
              for row in pairwise.itertuples() if row.note]
    ranks = rank_tests(clean, measure, within, subject, info.resolution) if info.rating else _empty(RANK_TEST_COLUMNS)
    result = MeasureResult(
        **base, anova=anova[ANOVA_RESULT_COLUMNS], simple_effects=simple, pairwise=pairwise, rank_tests=ranks,
        descriptives=cell_descriptives(clean, measure, within, subject),
        normality=residual_normality(values),
        order=order_check(clean, measure, within, subject, options.position), notes=tuple(filter(None, notes)))
    return result, clean


def unreadable_measure(df: pd.DataFrame, measure: str, within: Sequence[str], subject: str, problem: str
                       ) -> MeasureResult:
    """The result of a measure whose column holds values that are not numbers (``problem`` names them): a row per
    effect with the reason, nothing computed."""
    within = tuple(within)
    reason = f"not testable: {problem}"
    n_total = int(df[subject].nunique())
    return MeasureResult(
        measure=measure, within=within, subject=subject, info=MeasureInfo(measure), n_used=0, n_total=n_total,
        excluded=_empty(["subject", "reason"]), anova=untestable_rows(within, levels_of(df, within), 0, reason),
        simple_effects=_empty(SIMPLE_EFFECT_COLUMNS), pairwise=_empty(PAIRWISE_COLUMNS),
        rank_tests=_empty(RANK_TEST_COLUMNS), descriptives=_empty([*within, *DESCRIPTIVE_STATS]),
        normality=Normality(0, note=reason), order=OrderCheck(measure, 0, 0, note=reason), notes=(reason,),
        tested=False)


def levels_of(df: pd.DataFrame, within: Sequence[str]) -> list[int]:
    return [len(factor_levels(df, f)) for f in within]


def untestable_rows(within: Sequence[str], levels: Sequence[int], n: int, reason: str) -> pd.DataFrame:
    """One ANOVA row per effect with empty statistics and ``reason`` as its note (docs/analysis.md: nothing a
    study produces stops the analysis)."""
    rows = []
    for effect in effects_of(within):
        df1 = int(np.prod([max(levels[f] - 1, 0) for f in effect])) if levels else 0
        rows.append({"effect": effect_name(within, effect), "df1": df1, "df2": df1 * max(n - 1, 0),
                     "correction": "none", "note": reason})
    return pd.DataFrame(rows, columns=ANOVA_RESULT_COLUMNS)


def _empty(columns: list[str]) -> pd.DataFrame:
    return pd.DataFrame(columns=columns)
