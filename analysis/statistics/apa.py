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


def visible_digits(value: float, digits: int = 2, most: int = 4) -> int:
    """The decimals that show ``value``'s first significant digit: ``digits``, or more for a small non-zero value
    (η²G = .002, not .00), at most ``most``."""
    while digits < most and value != 0 and math.isfinite(value) and round(abs(value), digits) == 0:
        digits += 1
    return digits


def format_signed(value: float, significant: int = 3) -> str:
    """``value`` to ``significant`` significant digits (``-0.481``, ``3.25e-05``), a zero written ``0``."""
    text = f"{value:.{significant}g}"
    return "0" if float(text) == 0 else text


def format_df(df: float) -> str:
    """``26`` for whole degrees of freedom, ``25.47`` for corrected ones."""
    return str(round(df)) if float(df).is_integer() else f"{df:.2f}"


CORRECTIONS = {"GG": "Greenhouse–Geisser", "HF": "Huynh–Feldt"}


def apa_f_sentence(row: Mapping[str, Any]) -> str:
    """``F(1, 26) = 4.53, p = .043, η²G = .11`` from a row with ``df1, df2, F, p, ges``.

    A row of :mod:`analysis.statistics.anova` reads the degrees of freedom and p its ``correction`` names
    (``df1_read, df2_read, p_read``: ``F(2.43, 21.85) = 38.03, p < .001, η²G = .60, 90% CI [.48, .82]
    (Greenhouse–Geisser, ε = .49)``), adds the interval of η²G when the row has one, and says "not testable" with
    the reason when F could not be computed.
    """
    note = str(row.get("note") or "")
    if note.startswith("not testable"):
        return note
    corrected = "p_read" in row
    df1, df2 = (float(row["df1_read"]), float(row["df2_read"])) if corrected else (float(row["df1"]),
                                                                                   float(row["df2"]))
    f_value = float(row["F"])
    f_text = "n/a" if math.isnan(f_value) else f"{f_value:.2f}"
    ges = float(row["ges"])
    digits = visible_digits(ges)
    text = (f"F({format_df(df1)}, {format_df(df2)}) = {f_text}, "
            f"{p_clause(float(row['p_read'] if corrected else row['p']))}, "
            f"η²G = {format_proportion(ges, digits)}")
    if "ges_ci_low" in row and not math.isnan(float(row["ges_ci_low"])):
        text += f", 90% CI [{format_proportion(float(row['ges_ci_low']), digits)}, " \
                f"{format_proportion(float(row['ges_ci_high']), digits)}]"
    correction = str(row.get("correction") or "none")
    if correction in CORRECTIONS:
        eps = float(row["eps_gg"] if correction == "GG" else min(float(row["eps_hf"]), 1.0))
        text += f" ({CORRECTIONS[correction]}, ε = {format_proportion(eps)})"
    return text


def _no_leading_zero(value: float, digits: int) -> str:
    text = f"{value:.{digits}f}"
    if text.startswith("0."):
        return text[1:]
    if text.startswith("-0."):
        return "-" + text[2:]
    return text
