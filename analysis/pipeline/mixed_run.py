"""The statistics of one measure in a mixed design (``analyze --between``): complete cases, the mixed ANOVA
(:mod:`analysis.statistics.mixed_anova`), its follow-ups (:mod:`analysis.followups.mixed_followups`), descriptives per
group, the residual normality of the split-plot model and the order check.

The interval of η²G is a percentile bootstrap that resamples participants within their group. Not run for a mixed
design (the report says so): the rank tests of ratings, the paired-lines plot.
"""

from __future__ import annotations

import zlib
from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd

from analysis.followups.mixed_followups import mixed_descriptives, mixed_pairwise, mixed_simple_effects
from analysis.followups.pairwise import PAIRWISE_COLUMNS
from analysis.followups.simple_effects import SIMPLE_EFFECT_COLUMNS
from analysis.pipeline.measure_run import ANOVA_RESULT_COLUMNS, MIN_SUBJECTS, levels_of, untestable_rows
from analysis.preparation.cells import complete_cases, factor_levels, group_index, wide_matrix
from analysis.preparation.measure_info import MeasureInfo
from analysis.preparation.options import AnalysisOptions
from analysis.statistics.censoring import censoring_note
from analysis.statistics.descriptives import DESCRIPTIVE_STATS
from analysis.statistics.mixed_anova import mixed_anova_table, mixed_ges_bootstrap
from analysis.statistics.nonparametric import RANK_TEST_COLUMNS
from analysis.statistics.normality import Normality, residual_normality
from analysis.statistics.order_check import OrderCheck, order_check
from analysis.statistics.results import MeasureResult

NOT_RUN = "not run for a mixed design: rank tests, the paired-lines plot"


def analyze_mixed_measure(df: pd.DataFrame, measure: str, within: Sequence[str], between: str, subject: str,
                          info: MeasureInfo, options: AnalysisOptions,
                          why_missing: Mapping[tuple[object, str], str], censoring: pd.DataFrame | None
                          ) -> tuple[MeasureResult, pd.DataFrame]:
    """The result for ``measure`` (``within`` of the result: the between factor, then the within factors)."""
    within = tuple(within)
    clean, excluded = complete_cases(df, measure, within, subject, why_missing)
    n_used = int(clean[subject].nunique())
    groups = factor_levels(clean, between)
    factors = (between, *within)
    notes = [censoring_note(censoring, measure)] if censoring is not None else []
    base = {"measure": measure, "within": factors, "subject": subject, "info": info, "n_used": n_used,
            "n_total": int(df[subject].nunique()), "excluded": excluded}
    reason = ""
    if n_used <= len(groups) or len(groups) < 2:
        reason = (f"not testable: {n_used} participant(s) in {len(groups)} group(s) of {between} have a value in "
                  f"every cell of {' × '.join(within)}; at least two groups and {MIN_SUBJECTS} more "
                  "participants than groups are needed")
    elif clean[measure].nunique() == 1:
        reason = f"not testable: every value is {clean[measure].iloc[0]:g}, nothing varies"
    if reason:
        return MeasureResult(
            **base, anova=untestable_rows(factors, levels_of(df, factors), n_used, reason),
            simple_effects=pd.DataFrame(columns=SIMPLE_EFFECT_COLUMNS), pairwise=pd.DataFrame(columns=PAIRWISE_COLUMNS),
            rank_tests=pd.DataFrame(columns=RANK_TEST_COLUMNS),
            descriptives=pd.DataFrame(columns=[*factors, *DESCRIPTIVE_STATS]), normality=Normality(0, note=reason),
            order=OrderCheck(measure, n_used, 0, note=reason), notes=(reason, *filter(None, notes)),
            tested=False), clean
    values, subjects = wide_matrix(clean, measure, within, subject)
    index = group_index(clean, subjects, between, subject, groups)
    levels = levels_of(clean, within)
    anova = mixed_anova_table(values, index, len(groups), levels, within, between, ss_type=options.ss_type)
    rng = np.random.default_rng([options.seed, zlib.crc32(measure.encode())])
    intervals = mixed_ges_bootstrap(values, index, len(groups), levels, within, rng, ss_type=options.ss_type)
    anova["ges_ci_low"] = [low for low, _ in intervals]
    anova["ges_ci_high"] = [high for _, high in intervals]
    simple = mixed_simple_effects(clean, measure, within, between, subject, options.follow_up_error)
    pairwise = mixed_pairwise(clean, measure, within, between, subject, options.follow_up_error)
    notes += [f"{row.effect}: {row.note}" for row in anova.itertuples() if row.note]
    notes += [f"simple effect of {row.factor} at {row.at}: {row.note}" for row in simple.itertuples() if row.note]
    notes.append(NOT_RUN)
    result = MeasureResult(
        **base, anova=anova[ANOVA_RESULT_COLUMNS], simple_effects=simple, pairwise=pairwise,
        rank_tests=pd.DataFrame(columns=RANK_TEST_COLUMNS),
        descriptives=mixed_descriptives(clean, measure, within, between, subject),
        normality=residual_normality(_split_plot_residuals(values, np.array(index))),
        order=order_check(clean, measure, within, subject, options.position), notes=tuple(filter(None, notes)))
    return result, clean


def _split_plot_residuals(values: np.ndarray, groups: np.ndarray) -> np.ndarray:
    """y − participant mean − group's cell mean + group mean (the split-plot model's residuals)."""
    out = values - values.mean(axis=1, keepdims=True)
    for g in np.unique(groups):
        rows = groups == g
        out[rows] -= values[rows].mean(axis=0) - values[rows].mean()
    centred: np.ndarray = out
    return centred
