"""Result records of an analysis: one per measure, and the whole run.

Records hold pandas tables, so they compare by identity (``eq=False``) rather than by a field-wise
``==`` that pandas cannot answer with a single truth value.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import pandas as pd


@dataclass(frozen=True, slots=True, eq=False)
class MeasureResult:
    """Everything computed for one dependent variable.

    ``anova`` has the columns of ``analysis.anova.rm_anova_2way``; ``simple_effects`` those of
    ``simple_main_effects``; ``descriptives`` those of ``cell_descriptives``; ``excluded`` has
    ``subject, reason``. ``plots`` are paths relative to the output directory.
    """

    measure: str
    within: tuple[str, str]
    subject: str
    n_used: int
    n_total: int
    anova: pd.DataFrame
    simple_effects: pd.DataFrame
    descriptives: pd.DataFrame
    excluded: pd.DataFrame
    plots: tuple[str, ...]


@dataclass(frozen=True, slots=True, eq=False)
class AnalysisResult:
    """All measures of one run, the combined tables as written to CSV, and the files written."""

    measures: tuple[MeasureResult, ...]
    anova: pd.DataFrame
    simple_effects: pd.DataFrame
    descriptives: pd.DataFrame
    excluded: pd.DataFrame
    out_dir: Path
    files: tuple[Path, ...]
