"""Questionnaire scales: reverse coding, scale scores and their internal consistency.

* A reverse-coded rating item (``reverse: true``) on a min..max scale is reversed as max + min − value before it
  enters a scale (a 7 on a 1–7 item becomes a 1). Items analysed on their own keep the value as answered.
* A scale's score is the mean of its items after reversal, per participant and condition; a cell missing any of
  the scale's items has no score (no prorating), and the complete-case rule then says so.
* Cronbach's (1951) α per scale, over every participant × condition response and within each condition, with
  Feldt's 95 % CI (pingouin's ``cronbach_alpha``, listwise deletion). Responses of one participant in several
  conditions are not independent, so the pooled α is descriptive; the per-condition values are the ones to
  compare with published norms.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pandas as pd

from analysis.cells import cell_label, design_cells
from analysis.study_design import RatingItem, ScaleSpec

RELIABILITY_COLUMNS = ["scale", "condition", "n", "items", "alpha", "ci95_low", "ci95_high", "note"]
ALL_RESPONSES = "all conditions"


def reversed_values(values: pd.Series, item: RatingItem) -> pd.Series:
    """The item's values as they enter a scale: max + min − value when reverse-coded."""
    return item.maximum + item.minimum - values if item.reverse else values


def score_scales(cells: pd.DataFrame, items: Sequence[RatingItem], scales: Sequence[ScaleSpec]) -> pd.DataFrame:
    """``cells`` with one column per scale (the mean of its items after reversal; NaN if one is missing)."""
    by_column = {item.column: item for item in items}
    out = cells.copy()
    for scale in scales:
        present = [c for c in scale.items if c in out.columns]
        if not present:
            out[scale.column] = np.nan
            continue
        scored = pd.concat([reversed_values(out[c].astype(float), by_column[c]) for c in present], axis=1)
        out[scale.column] = scored.mean(axis=1, skipna=False)
    return out


def response_scores(values: Mapping[str, Any], items: Sequence[RatingItem], scales: Sequence[ScaleSpec]
                    ) -> dict[str, float | None]:
    """The scores of one response (``values``: item column → answer, absent or ``None`` when not answered), scored
    as :func:`score_scales` scores a table; ``None`` for a scale missing an item."""
    answers = pd.DataFrame([{c: values.get(c) for scale in scales for c in scale.items}], dtype=float)
    scored = score_scales(answers, items, scales)
    return {s.column: None if pd.isna(scored[s.column].iloc[0]) else float(scored[s.column].iloc[0])
            for s in scales}


def scale_reliability(cells: pd.DataFrame, items: Sequence[RatingItem], scales: Sequence[ScaleSpec],
                      within: Sequence[str]) -> pd.DataFrame:
    """α of every scale with at least two items: pooled over all responses, then per condition."""
    by_column = {item.column: item for item in items}
    rows = []
    for scale in scales:
        columns = [c for c in scale.items if c in cells.columns]
        if len(columns) < 2:
            rows.append({"scale": scale.column, "condition": ALL_RESPONSES, "n": len(cells),
                         "items": len(columns), "note": "not applicable: α needs at least two items"})
            continue
        scored = pd.DataFrame({c: reversed_values(cells[c].astype(float), by_column[c]) for c in columns})
        rows.append({"scale": scale.column, "condition": ALL_RESPONSES, **cronbach(scored)})
        if within:
            labels = [cell_label(within, tuple(r)) for r in cells[list(within)].itertuples(index=False)]
            for label in (cell_label(within, cell) for cell in design_cells(cells, within)):
                mask = np.array([x == label for x in labels])
                rows.append({"scale": scale.column, "condition": label, **cronbach(scored[mask])})
    return pd.DataFrame(rows, columns=RELIABILITY_COLUMNS)


def cronbach(items: pd.DataFrame) -> dict[str, object]:
    """n (complete responses), number of items, α and its 95 % CI, or a note when α cannot be computed."""
    import pingouin as pg

    complete = items.dropna()
    out: dict[str, object] = {"n": len(complete), "items": items.shape[1], "alpha": np.nan, "ci95_low": np.nan,
                              "ci95_high": np.nan, "note": ""}
    if len(complete) < 3:
        out["note"] = "not computable: fewer than 3 complete responses"
    elif complete.sum(axis=1).var(ddof=1) == 0:
        out["note"] = "not computable: every response has the same total"
    else:
        alpha, ci = pg.cronbach_alpha(data=complete, nan_policy="listwise")
        out.update(alpha=float(alpha), ci95_low=float(ci[0]), ci95_high=float(ci[1]))
    return out
