"""Complete-case handling for a within-subject design.

A repeated-measures ANOVA needs every subject in every cell of the within design (the full crossing
of the levels of the within factors), each cell holding one value of the dependent variable.
Subjects that lack a cell, or whose value in a cell is missing (NaN), are removed as a whole
(listwise deletion), and the reason is kept so that the report can say who was excluded and why.
R's ``afex::aov_ez`` and JASP do the same (with a warning), pingouin does it silently; here it is
done explicitly and reported.
"""

from __future__ import annotations

import itertools
from collections.abc import Hashable, Iterable, Iterator, Mapping, Sequence
from typing import Any

import numpy as np
import pandas as pd

from analysis.source.input_errors import AnalysisInputError
from analysis.source.naming import cell_label

Cell = tuple[Any, ...]


def require_columns(df: pd.DataFrame, columns: Iterable[str]) -> None:
    """Raise ``AnalysisInputError`` naming the first of ``columns`` that ``df`` lacks."""
    for column in columns:
        if column not in df.columns:
            available = ", ".join(repr(str(c)) for c in df.columns) or "none"
            raise AnalysisInputError(
                f"column {column!r} not found in the table; available columns: {available}"
            )


def factor_levels(df: pd.DataFrame, factor: str) -> list[Any]:
    """Levels of ``factor`` present in ``df``: the category order if categorical (the study's order, see
    :mod:`analysis.preparation.levels`), else the order of first appearance."""
    column = df[factor]
    if isinstance(column.dtype, pd.CategoricalDtype):
        present = set(column.dropna().unique())
        return [level for level in column.cat.categories if level in present]
    return list(pd.unique(column.dropna()))


def design_cells(df: pd.DataFrame, within: Sequence[str]) -> list[Cell]:
    """Every cell of the within design in design order (the first factor varies slowest, levels in
    :func:`factor_levels` order: the study's)."""
    return list(itertools.product(*(factor_levels(df, f) for f in within)))


NAMED_VALUES = 3
"""How many offending values a message quotes."""


def non_numeric_values(df: pd.DataFrame, dv: str, within: Sequence[str], subject: str) -> str:
    """Empty when ``dv`` is numeric (or holds only numbers written as text and empty cells); else which rows hold
    what: ``2 values are not numbers: row 7 (participant P03, robot=baseline, kitchen=mid_2): 'n/a'; …`` (rows
    counted from 1, the header not counted)."""
    if pd.api.types.is_numeric_dtype(df[dv]) or dv not in df.columns:
        return ""
    coerced = pd.to_numeric(df[dv], errors="coerce")
    bad = df[df[dv].notna() & coerced.isna() & (df[dv].astype(str).str.strip() != "")]
    if bad.empty:
        return ""
    named = [f"row {position + 1} ({subject} {row[subject]}, {cell_label(within, tuple(row[f] for f in within))}): "
             f"{row[dv]!r}" for position, (_, row) in zip(
                 (df.index.get_loc(i) for i in bad.index), bad.iterrows(), strict=True)][:NAMED_VALUES]
    more = f"; and {len(bad) - NAMED_VALUES} more" if len(bad) > NAMED_VALUES else ""
    return (f"{len(bad)} value(s) of {dv} are not numbers: " + "; ".join(named) + more)


def non_finite_values(df: pd.DataFrame, dv: str, within: Sequence[str], subject: str) -> str:
    """Empty unless numeric ``dv`` holds an infinite value (``inf`` in a CSV file reads as a number); else which
    rows: ``1 value(s) of ticks are not finite: row 4 (participant P01, robot=fov_aware, kitchen=none_3): inf``."""
    if dv not in df.columns or not pd.api.types.is_numeric_dtype(df[dv]):
        return ""
    values = df[dv].astype(float)
    bad = df[np.isinf(values)]
    if bad.empty:
        return ""
    named = [f"row {df.index.get_loc(i) + 1} ({subject} {row[subject]}, "
             f"{cell_label(within, tuple(row[f] for f in within))}): {row[dv]}"
             for i, row in bad.head(NAMED_VALUES).iterrows()]
    more = f"; and {len(bad) - NAMED_VALUES} more" if len(bad) > NAMED_VALUES else ""
    return f"{len(bad)} value(s) of {dv} are not finite: " + "; ".join(named) + more


def validate_design(df: pd.DataFrame, dv: str, within: Sequence[str], subject: str) -> None:
    """Check the columns, their types and the one-row-per-subject-and-cell shape of ``df``.

    Raises ``AnalysisInputError`` for a missing column, a non-numeric ``dv``, an empty subject or
    factor value, a factor with fewer than two levels, or two rows for one subject and cell.
    """
    roles = [dv, *within, subject]
    if len(set(roles)) != len(roles):
        raise AnalysisInputError(
            f"dv, within factors and subject must be distinct columns: {roles}"
        )
    require_columns(df, roles)
    if not pd.api.types.is_numeric_dtype(df[dv]):
        raise AnalysisInputError(
            f"column {dv!r} is the dependent variable but is not numeric (dtype {df[dv].dtype})"
        )
    for column in [subject, *within]:
        empty = int(df[column].isna().sum())
        if empty:
            raise AnalysisInputError(
                f"column {column!r} has {empty} empty value(s); every row needs a subject "
                "and a level of each within factor"
            )
    for factor in within:
        levels = factor_levels(df, factor)
        if len(levels) < 2:
            raise AnalysisInputError(
                f"within factor {factor!r} has {len(levels)} level(s) {levels}; "
                "a repeated-measures factor needs at least two"
            )
    doubled = df[df.duplicated([subject, *within], keep=False)]
    if not doubled.empty:
        first = doubled.iloc[0]
        cell = tuple(first[f] for f in within)
        raise AnalysisInputError(
            f"subject {first[subject]} has more than one row in cell {cell_label(within, cell)}; "
            "the analysis needs one row per subject and cell (aggregate trials first)"
        )


def complete_cases(
    df: pd.DataFrame, dv: str, within: Sequence[str], subject: str,
    why_missing: Mapping[tuple[Any, str], str] | None = None,
) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Split ``df`` into the subjects with a value in every within cell and the others.

    Returns ``(clean, excluded)``: ``clean`` holds all rows of the complete subjects (original
    columns, original order); ``excluded`` has one row per removed subject with columns
    ``subject, reason``, the reason naming each missing cell (``missing cell robot=baseline,
    kitchen=mid_2``, followed by ``(why)`` when ``why_missing`` has the subject and cell label) or
    missing value (``missing value of ticks in cell ...``), joined by ``; ``.
    """
    within = list(within)
    validate_design(df, dv, within, subject)
    cells: list[Cell] = list(itertools.product(*(factor_levels(df, f) for f in within)))
    observed = {(row[0], *row[1:-1]): row[-1] for row in
                df[[subject, *within, dv]].astype(object).itertuples(index=False, name=None)}
    kept: list[Hashable] = []
    excluded: list[dict[str, Any]] = []
    for subject_id in sorted(pd.unique(df[subject]), key=_subject_key):
        problems = []
        for cell in cells:
            key = (subject_id, *cell)
            if key not in observed:
                label = cell_label(within, cell)
                why = (why_missing or {}).get((subject_id, label))
                problems.append(f"missing cell {label}" + (f" ({why})" if why else ""))
            elif pd.isna(observed[key]):
                problems.append(f"missing value of {dv} in cell {cell_label(within, cell)}")
        if problems:
            excluded.append({"subject": subject_id, "reason": "; ".join(problems)})
        else:
            kept.append(subject_id)
    clean = df[df[subject].isin(kept)].reset_index(drop=True)
    return clean, pd.DataFrame(excluded, columns=["subject", "reason"])


def require_complete(df: pd.DataFrame, dv: str, within: Sequence[str], subject: str) -> None:
    """Raise ``AnalysisInputError`` unless every subject has a value in every within cell."""
    _, excluded = complete_cases(df, dv, within, subject)
    if not excluded.empty:
        first = excluded.iloc[0]
        raise AnalysisInputError(
            f"{len(excluded)} subject(s) lack cells for {dv!r}, e.g. subject {first['subject']}: "
            f"{first['reason']}; drop them with analysis.preparation.cells.complete_cases first"
        )


def slices(df: pd.DataFrame, within: Sequence[str], factor: str) -> Iterator[tuple[str, pd.DataFrame]]:
    """``(label, rows)`` for each combination of the levels of the factors other than ``factor``, in design order
    (``kitchen=mid_2``: the rows of ``df`` in that kitchen)."""
    others = [f for f in within if f != factor]
    for combo in itertools.product(*(factor_levels(df, f) for f in others)):
        mask = pd.Series(True, index=df.index)
        for other, level in zip(others, combo, strict=True):
            mask &= df[other] == level
        yield cell_label(others, combo), df[mask]


def wide_matrix(df: pd.DataFrame, dv: str, within: Sequence[str], subject: str) -> tuple[np.ndarray, list[Any]]:
    """``(Y, subjects)``: ``Y[s, c]`` is subject s's value in cell c, cells in design order (the first factor
    varies slowest, levels in :func:`factor_levels` order). ``df`` must be complete (see :func:`complete_cases`)."""
    within = list(within)
    require_complete(df, dv, within, subject)
    levels = [factor_levels(df, f) for f in within]
    cells = list(itertools.product(*levels))
    subjects = list(pd.unique(df[subject]))
    table = df.set_index([subject, *within])[dv].astype(float)
    index = pd.MultiIndex.from_tuples([(s, *cell) for s in subjects for cell in cells])
    values = table.reindex(index).to_numpy(dtype=float).reshape(len(subjects), len(cells))
    return values, subjects


def group_index(df: pd.DataFrame, subjects: Sequence[Any], between: str, subject: str, groups: Sequence[Any]
                ) -> list[int]:
    """Each of ``subjects``' group in ``df`` (one level of ``between`` per participant) as its index in ``groups``:
    the row groups of :func:`wide_matrix`'s ``Y`` for a mixed design."""
    group_of = df.drop_duplicates(subject).set_index(subject)[between]
    order = list(groups)
    return [order.index(group_of[s]) for s in subjects]


def _subject_key(subject: Any) -> tuple[int, Any]:
    """Subjects in order: numbers numerically, everything else as text."""
    if isinstance(subject, int | float) and not isinstance(subject, bool):
        return (0, subject)
    return (1, str(subject))
