"""Result records of an analysis: one per measure, and the whole run.

Records hold pandas tables, so they compare by identity (``eq=False``) rather than by a field-wise
``==`` that pandas cannot answer with a single truth value.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import pandas as pd

from analysis.preparation.measure_info import MeasureInfo
from analysis.statistics.normality import Normality
from analysis.statistics.order_check import OrderCheck


@dataclass(frozen=True, slots=True, eq=False)
class MeasureResult:
    """Everything computed for one dependent variable.

    ``anova`` has the columns of ``analysis.statistics.anova.ANOVA_COLUMNS`` plus ``ges_ci_low, ges_ci_high``;
    ``simple_effects``, ``pairwise``, ``rank_tests`` and ``descriptives`` those of their modules (empty when they
    do not apply); ``excluded`` has ``subject, reason``. ``notes`` are the warnings and explanations the report
    prints for the measure (a test that could not be computed, a censored cell, a clipped error bar); ``plots``
    are paths relative to the output directory.
    """

    measure: str
    within: tuple[str, ...]
    subject: str
    info: MeasureInfo
    n_used: int
    n_total: int
    anova: pd.DataFrame
    simple_effects: pd.DataFrame
    pairwise: pd.DataFrame
    rank_tests: pd.DataFrame
    descriptives: pd.DataFrame
    excluded: pd.DataFrame
    normality: Normality
    order: OrderCheck
    notes: tuple[str, ...] = ()
    plots: tuple[str, ...] = ()
    tested: bool = True
    """Whether the ANOVA could be run at all (at least two complete participants, a measure that varies, numeric
    values); when not, ``anova`` has a row per effect with the reason as its note."""

    @property
    def testable(self) -> bool:
        return self.tested


@dataclass(frozen=True, slots=True, eq=False)
class AnalysisResult:
    """All measures of one run, the combined tables as written to CSV (by file name), the run's warnings and the
    files written."""

    measures: tuple[MeasureResult, ...]
    tables: dict[str, pd.DataFrame]
    warnings: tuple[str, ...]
    out_dir: Path
    files: tuple[Path, ...]
    checked_rules: tuple[str, ...] = ()
    """Exclusion rules whose column the table has (:mod:`analysis.preparation.exclusions`)."""
    formulas: tuple[str, ...] = ()
    """The linear mixed models' formulas (``--model lmm``), as printed."""

    @property
    def anova(self) -> pd.DataFrame:
        return self.tables["anova.csv"]

    @property
    def simple_effects(self) -> pd.DataFrame:
        return self.tables["simple_effects.csv"]
