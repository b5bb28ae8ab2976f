"""Censoring of ticks at the horizon and the paired tests of finished (analysis.statistics.censoring)."""

from __future__ import annotations

import itertools

import pandas as pd
import pytest

from analysis.statistics.censoring import censoring_note, censoring_table, finished_tests


def agresti_drugs() -> pd.DataFrame:
    """The drug-response data of Agresti (2002), Categorical Data Analysis, used in the Cochran's Q example of
    SAS/STAT's PROC FREQ documentation and of R DescTools' ``CochranQTest``: 46 subjects rate drugs A, B, C
    favourable (1) or not (0); response patterns (A, B, C) with their counts."""
    patterns = {(1, 1, 1): 6, (1, 1, 0): 16, (1, 0, 1): 2, (1, 0, 0): 4, (0, 1, 1): 2, (0, 1, 0): 4,
                (0, 0, 1): 6, (0, 0, 0): 6}
    rows, subject = [], 0
    for pattern, count in patterns.items():
        for _ in range(count):
            subject += 1
            rows += [{"s": subject, "drug": d, "finished": v} for d, v in zip("ABC", pattern, strict=True)]
    return pd.DataFrame(rows)


def test_cochran_q_matches_agresti() -> None:
    # SAS PROC FREQ and DescTools: Cochran's Q = 8.4706, df = 2, p = 0.0145.
    row = finished_tests(agresti_drugs(), ["drug"], "s").iloc[0]
    assert row["test"] == "Cochran's Q" and row["df"] == 2
    assert row["statistic"] == pytest.approx(8.4706, abs=5e-5) and round(row["p"], 4) == 0.0145


def test_exact_mcnemar_matches_fagerland() -> None:
    # Fagerland, Lydersen & Laake (2013), BMC Med Res Methodol 13:91, the airway example: 1 and 7 discordant pairs
    # give the exact conditional p = 0.070 (2 × P(X ≤ 1), X ~ Bin(8, 1/2) = 18/256).
    rows = []
    for s, (a, b) in enumerate([(1, 1)] * 10 + [(0, 0)] * 3 + [(1, 0)] * 1 + [(0, 1)] * 7):
        rows += [{"s": s, "robot": "x", "finished": a}, {"s": s, "robot": "y", "finished": b}]
    row = finished_tests(pd.DataFrame(rows), ["robot"], "s").iloc[0]
    assert row["test"] == "McNemar (exact)" and row["p"] == pytest.approx(18 / 256) and round(row["p"], 3) == 0.070


def test_censored_cells_are_counted_and_noted_for_ticks_only() -> None:
    rows = [{"s": s, "robot": r, "kitchen": k, "finished": int(not (r == "b" and k == "k2" and s < 2))}
            for s, r, k in itertools.product(range(5), "ab", ("k1", "k2"))]
    df = pd.DataFrame(rows)
    table = censoring_table(df, ["robot", "kitchen"])
    assert table["cell"].tolist() == ["robot=a, kitchen=k1", "robot=a, kitchen=k2", "robot=b, kitchen=k1",
                                      "robot=b, kitchen=k2"]
    assert table["reached_horizon"].tolist() == [0, 0, 0, 2] and table["share"].tolist()[-1] == pytest.approx(0.4)
    note = censoring_note(table, "ticks")
    assert "censored at the horizon in 1 cell(s) (robot=b, kitchen=k2: 2 of 5 trials" in note
    assert censoring_note(table, "kb_gap_mean") == ""
    tests = finished_tests(df, ["robot", "kitchen"], "s")
    assert list(zip(tests["factor"], tests["at"], strict=True))[:3] == [
        ("all conditions", ""), ("robot", "kitchen=k1"), ("robot", "kitchen=k2")]
    assert tests.iloc[1]["note"] == "not testable: every trial finished"


def test_participants_who_always_or_never_finish_are_not_testable() -> None:
    rows = [{"s": s, "robot": r, "finished": int(s % 2)} for s in range(6) for r in "abc"]
    row = finished_tests(pd.DataFrame(rows), ["robot"], "s").iloc[0]
    assert row["note"] == "not testable: every participant finished in all of these conditions or in none"
