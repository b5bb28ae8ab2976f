"""``analyze_long``: the whole statistics pipeline for a long table, written to one folder.

For each measure (dependent variable): complete cases (``analysis.cells``), the two-way RM-ANOVA
and the simple main effects of the first within factor within each level of the second
(``analysis.anova``; robot within kitchen in the Steakhouse study, paper §VII), cell descriptives
with within-subject CIs (``analysis.descriptives``), an interaction plot and a paired-lines plot
(``analysis.plots``). Then the combined CSV files and the report.

Files written into ``out_dir``::

    anova.csv           measure, effect, df1, df2, SS, F, p, ges, partial_eta2
    simple_effects.csv  measure, level, effect, df1, df2, F, p, p_holm, ges
    descriptives.csv    measure, <within factors>, n, mean, sd, se_ws, ci95_low, ci95_high
    excluded.csv        measure, subject, reason
    plots/<measure>_interaction.png|.svg, plots/<measure>_paired.png|.svg
    report.md, report.html
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path

import pandas as pd

from analysis.anova import rm_anova_2way, simple_main_effects
from analysis.cells import complete_cases, require_columns
from analysis.descriptives import DESCRIPTIVE_STATS, cell_descriptives
from analysis.errors import AnalysisInputError
from analysis.plots import interaction_plot, paired_plot
from analysis.report import write_report
from analysis.results import AnalysisResult, MeasureResult

ANOVA_CSV_COLUMNS = ["measure", "effect", "df1", "df2", "SS", "F", "p", "ges", "partial_eta2"]
SIMPLE_CSV_COLUMNS = ["measure", "level", "effect", "df1", "df2", "F", "p", "p_holm", "ges"]
EXCLUDED_CSV_COLUMNS = ["measure", "subject", "reason"]
MIN_SUBJECTS = 2


def analyze_long(
    df: pd.DataFrame,
    measures: Sequence[str],
    within: Sequence[str],
    subject: str,
    out_dir: Path | str,
) -> AnalysisResult:
    """Analyse each of ``measures`` in the long table ``df`` and write the results to ``out_dir``.

    ``within = [A, B]``: simple main effects of A are tested within each level of B. Raises
    ``AnalysisInputError`` for a missing column, a malformed design, or a measure with fewer than
    two complete subjects; nothing is written then.
    """
    factors = _check_arguments(df, measures, within, subject)
    out = Path(out_dir)
    analysed = [_analyze_measure(df, m, factors, subject) for m in measures]

    out.mkdir(parents=True, exist_ok=True)
    files: list[Path] = []
    final = []
    for (result, clean), stem in zip(analysed, _file_stems(measures), strict=True):
        plot_dir = out / "plots"
        plots = interaction_plot(
            result.descriptives, result.measure, factors, plot_dir / f"{stem}_interaction"
        )
        plots += paired_plot(clean, result.measure, factors, subject, plot_dir / f"{stem}_paired")
        files += plots
        final.append(replace(result, plots=tuple(p.relative_to(out).as_posix() for p in plots)))

    anova = _stack(final, "anova", ANOVA_CSV_COLUMNS)
    simple = _stack(final, "simple_effects", SIMPLE_CSV_COLUMNS)
    descriptives = _stack(final, "descriptives", ["measure", *factors, *DESCRIPTIVE_STATS])
    excluded = _stack(final, "excluded", EXCLUDED_CSV_COLUMNS)
    for name, frame in [
        ("anova.csv", anova),
        ("simple_effects.csv", simple),
        ("descriptives.csv", descriptives),
        ("excluded.csv", excluded),
    ]:
        frame.to_csv(out / name, index=False)
        files.append(out / name)
    files += write_report(final, out)
    return AnalysisResult(
        measures=tuple(final),
        anova=anova,
        simple_effects=simple,
        descriptives=descriptives,
        excluded=excluded,
        out_dir=out,
        files=tuple(files),
    )


def _analyze_measure(
    df: pd.DataFrame, measure: str, within: tuple[str, str], subject: str
) -> tuple[MeasureResult, pd.DataFrame]:
    """The statistics of one measure, and the complete-case table they were computed from."""
    clean, excluded = complete_cases(df, measure, within, subject)
    n_used = int(clean[subject].nunique())
    if n_used < MIN_SUBJECTS:
        raise AnalysisInputError(
            f"measure {measure!r}: {n_used} subject(s) have a value in every cell of "
            f"{' × '.join(within)}; at least {MIN_SUBJECTS} are needed"
        )
    a, b = within
    result = MeasureResult(
        measure=measure,
        within=within,
        subject=subject,
        n_used=n_used,
        n_total=int(df[subject].nunique()),
        anova=rm_anova_2way(clean, measure, within, subject),
        simple_effects=simple_main_effects(clean, measure, a, b, subject),
        descriptives=cell_descriptives(clean, measure, within, subject),
        excluded=excluded,
        plots=(),
    )
    return result, clean


def _check_arguments(
    df: pd.DataFrame, measures: Sequence[str], within: Sequence[str], subject: str
) -> tuple[str, str]:
    if isinstance(measures, str):
        raise AnalysisInputError(
            f"measures must be a list of column names, got the string {measures!r}"
        )
    if not measures:
        raise AnalysisInputError("no measure given")
    if len(set(measures)) != len(measures):
        raise AnalysisInputError(f"a measure is named twice: {list(measures)}")
    if len(within) != 2:
        raise AnalysisInputError(
            f"the analysis needs exactly two within factors, got {list(within)}"
        )
    require_columns(df, [*within, subject, *measures])
    return within[0], within[1]


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


def _stack(results: list[MeasureResult], attribute: str, columns: list[str]) -> pd.DataFrame:
    frames = [getattr(r, attribute).assign(measure=r.measure) for r in results]
    non_empty = [frame for frame in frames if not frame.empty]
    if not non_empty:
        return pd.DataFrame(columns=columns)
    return pd.concat(non_empty, ignore_index=True)[columns]
