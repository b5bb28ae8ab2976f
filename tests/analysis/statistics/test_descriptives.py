"""Cousineau–Morey within-subject CIs against a hand computation."""

from __future__ import annotations

import math

import pandas as pd
import pytest

from analysis.statistics.descriptives import cell_descriptives

T_975_DF2 = 4.302652729749464  # Student t, 97.5th percentile, 2 degrees of freedom


def tiny() -> pd.DataFrame:
    """3 subjects × (a1, a2) × (b1, b2); subject means 2, 4, 6, grand mean 4."""
    values = {
        "s1": [1, 1, 2, 4],
        "s2": [2, 4, 4, 6],
        "s3": [2, 5, 7, 10],
    }
    cells = [("a1", "b1"), ("a1", "b2"), ("a2", "b1"), ("a2", "b2")]
    rows = [
        {"s": s, "A": a, "B": b, "y": float(v)}
        for s, ys in values.items()
        for (a, b), v in zip(cells, ys, strict=True)
    ]
    return pd.DataFrame(rows)


def test_cousineau_morey_by_hand() -> None:
    # Normalised y' = y - subject mean + 4:  s1 -> 3 3 4 6,  s2 -> 2 4 4 6,  s3 -> 0 3 5 8.
    # Cell variances of y' (n-1 = 2): 7/3, 1/3, 1/3, 4/3.  Morey factor C/(C-1) = 4/3, n = 3:
    # se_ws = sqrt(var' * 4/3 / 3).
    desc = cell_descriptives(tiny(), "y", ["A", "B"], "s")
    assert list(desc.columns) == ["A", "B", "n", "mean", "sd", "se_ws", "ci95_low", "ci95_high"]
    assert desc[["A", "B"]].values.tolist() == [
        ["a1", "b1"],
        ["a1", "b2"],
        ["a2", "b1"],
        ["a2", "b2"],
    ]
    assert desc["n"].tolist() == [3, 3, 3, 3]
    assert desc["mean"].to_numpy() == pytest.approx([5 / 3, 10 / 3, 13 / 3, 20 / 3])
    raw_var = [1 / 3, 13 / 3, 19 / 3, 28 / 3]  # raw cell values 1 2 2 | 1 4 5 | 2 4 7 | 4 6 10
    assert desc["sd"].to_numpy() == pytest.approx([math.sqrt(v) for v in raw_var])
    se = [math.sqrt(v * 4 / 3 / 3) for v in (7 / 3, 1 / 3, 1 / 3, 4 / 3)]
    assert desc["se_ws"].to_numpy() == pytest.approx(se)
    half = [T_975_DF2 * x for x in se]
    means = [5 / 3, 10 / 3, 13 / 3, 20 / 3]
    assert desc["ci95_low"].to_numpy() == pytest.approx([m - h for m, h in zip(means, half, strict=True)])
    assert desc["ci95_high"].to_numpy() == pytest.approx([m + h for m, h in zip(means, half, strict=True)])


def test_subject_offsets_do_not_widen_the_interval() -> None:
    df = tiny()
    shifted = df.assign(y=df["y"] + df["s"].map({"s1": -50.0, "s2": 0.0, "s3": 80.0}))
    a = cell_descriptives(df, "y", ["A", "B"], "s")
    b = cell_descriptives(shifted, "y", ["A", "B"], "s")
    assert b["se_ws"].to_numpy() == pytest.approx(a["se_ws"].to_numpy())
    assert (b["sd"] > a["sd"]).all()
