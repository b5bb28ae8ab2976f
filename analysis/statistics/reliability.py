"""The internal consistency of questionnaire scales: Cronbach's (1951) α.

α per scale, over every participant × condition response and within each condition, with Feldt's 95 % CI
(pingouin's ``cronbach_alpha``, listwise deletion), on the items after reversal
(:func:`analysis.measures.scale_scores.reversed_values`). Responses of one participant in several conditions are
not independent, so the pooled α is descriptive; the per-condition values are the ones to compare with published
norms.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pandas as pd

from analysis.measures.scale_scores import reversed_values
from analysis.preparation.cells import design_cells
from analysis.source.naming import cell_label
from analysis.source.study_design import RatingItem, ScaleSpec

RELIABILITY_COLUMNS = ["scale", "condition", "n", "items", "alpha", "ci95_low", "ci95_high", "note"]
ALL_RESPONSES = "all conditions"


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
