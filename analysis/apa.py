"""APA-style formatting of test results (APA Publication Manual, 7th ed., §6.36 and §6.44).

Statistics that cannot exceed 1 (p, η²) are written without a leading zero; p is given to three
decimals, and as ``< .001`` below that; F to two decimals; degrees of freedom as integers (two
decimals if corrected, hence fractional).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any


def format_p(p: float) -> str:
    """``.043``, ``< .001``, or ``> .999`` when three decimals would read 1.000; ``n/a`` for NaN."""
    if math.isnan(p):
        return "n/a"
    if p < 0.001:
        return "< .001"
    text = _no_leading_zero(p, 3)
    return "> .999" if text == "1.000" else text


def p_clause(p: float) -> str:
    """``p = .043`` or ``p < .001``: the p part of a sentence."""
    text = format_p(p)
    return f"p {text}" if text[0] in "<>" else f"p = {text}"


def format_proportion(value: float, digits: int = 2) -> str:
    """A statistic bounded by ±1 (η², r) without its leading zero: ``.11``, ``-.05``, ``1.00``."""
    if math.isnan(value):
        return "n/a"
    return _no_leading_zero(value, digits)


def format_df(df: float) -> str:
    """``26`` for whole degrees of freedom, ``25.47`` for corrected ones."""
    return str(int(round(df))) if float(df).is_integer() else f"{df:.2f}"


def apa_f_sentence(row: Mapping[str, Any]) -> str:
    """``F(1, 26) = 4.53, p = .043, η²G = .11`` from a row with ``df1, df2, F, p, ges``."""
    f_value = float(row["F"])
    f_text = "n/a" if math.isnan(f_value) else f"{f_value:.2f}"
    return (
        f"F({format_df(float(row['df1']))}, {format_df(float(row['df2']))}) = {f_text}, "
        f"{p_clause(float(row['p']))}, η²G = {format_proportion(float(row['ges']))}"
    )


def _no_leading_zero(value: float, digits: int) -> str:
    text = f"{value:.{digits}f}"
    if text.startswith("0."):
        return text[1:]
    if text.startswith("-0."):
        return "-" + text[2:]
    return text
