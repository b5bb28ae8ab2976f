"""APA number formatting."""

from __future__ import annotations

import math

import pytest

from analysis.statistics.apa import apa_f_sentence, format_df, format_p, format_proportion, p_clause


@pytest.mark.parametrize(
    ("p", "text"),
    [
        (0.043, ".043"),
        (0.0429, ".043"),
        (0.5, ".500"),
        (0.001, ".001"),
        (0.00099, "< .001"),
        (1e-12, "< .001"),
        (0.9994, ".999"),
        (0.9999, "> .999"),
        (math.nan, "n/a"),
    ],
)
def test_format_p(p: float, text: str) -> None:
    assert format_p(p) == text


def test_p_clause_uses_equals_only_for_exact_values() -> None:
    assert p_clause(0.043) == "p = .043"
    assert p_clause(0.0001) == "p < .001"


def test_sentence_matches_the_product_example() -> None:
    row = {"df1": 1, "df2": 26, "F": 4.529, "p": 0.0429, "ges": 0.1123}
    assert apa_f_sentence(row) == "F(1, 26) = 4.53, p = .043, η²G = .11"


def test_sentence_with_tiny_p_and_float_dfs() -> None:
    row = {"df1": 1.0, "df2": 9.0, "F": 33.85228, "p": 2.5e-4, "ges": 0.25401}
    assert apa_f_sentence(row) == "F(1, 9) = 33.85, p < .001, η²G = .25"


def test_corrected_df_and_proportions() -> None:
    assert format_df(25.4712) == "25.47"
    assert format_df(18.0) == "18"
    assert format_proportion(0.0841, 3) == ".084"
    assert format_proportion(1.0) == "1.00"
    assert format_proportion(-0.05) == "-.05"
