"""Published datasets and the check that a computed value agrees with a published one to every digit printed.

Each dataset cites where it and its reference values are published; the tests cite the values they compare.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

# Maxwell & Delaney (2004), Designing Experiments and Analyzing Data, Table 12.1 (reaction time in ms of 10
# subjects, noise absent/present × target at 0°, 4°, 8°), as printed in R's documentation (?SSD, ?anova.mlm,
# ?mauchly.test: the matrix "reacttime", columns deg0NA deg4NA deg8NA deg0NP deg4NP deg8NP). R's outputs for it
# are saved in R's sources, tests/Examples/stats-Ex.Rout.save.
REACTTIME = np.array([
    [420, 420, 480, 480, 600, 780],
    [420, 480, 480, 360, 480, 600],
    [480, 480, 540, 660, 780, 780],
    [420, 540, 540, 480, 780, 900],
    [540, 660, 540, 480, 660, 720],
    [360, 420, 360, 360, 480, 540],
    [480, 480, 600, 540, 720, 840],
    [480, 600, 660, 540, 720, 900],
    [540, 600, 540, 480, 720, 780],
    [480, 420, 540, 540, 660, 780],
], dtype=float)

# Hollander & Wolfe (1973), p. 140: times rounding first base with three methods, 22 players (R's ?friedman.test,
# "RoundingTimes"; R prints Friedman chi-squared = 11.1429, df = 2, p-value = 0.003805).
ROUNDING_TIMES = np.array([
    [5.40, 5.50, 5.55], [5.85, 5.70, 5.75], [5.20, 5.60, 5.50], [5.55, 5.50, 5.40], [5.90, 5.85, 5.70],
    [5.45, 5.55, 5.60], [5.40, 5.40, 5.35], [5.45, 5.50, 5.35], [5.25, 5.15, 5.00], [5.85, 5.80, 5.70],
    [5.25, 5.20, 5.10], [5.65, 5.55, 5.45], [5.60, 5.35, 5.45], [5.05, 5.00, 4.95], [5.50, 5.50, 5.40],
    [5.45, 5.55, 5.50], [5.55, 5.55, 5.35], [5.45, 5.50, 5.55], [5.50, 5.45, 5.25], [5.65, 5.60, 5.40],
    [5.70, 5.65, 5.55], [6.30, 6.30, 6.25],
])

# Hollander & Wolfe (1973), p. 29f: Hamilton depression scale of 9 patients at the first (x) and second (y)
# visit (R's ?wilcox.test prints V = 40, p-value = 0.01953 for alternative = "greater").
DEPRESSION_X = np.array([1.83, 0.50, 1.62, 2.48, 1.68, 1.88, 1.55, 3.06, 1.30])
DEPRESSION_Y = np.array([0.878, 0.647, 0.598, 2.05, 1.06, 1.29, 1.06, 3.14, 1.29])

# JASP's one-sample t test of 18 proportions against 0.5 (jasp-stats/jaspTTests,
# tests/testthat/test-ttestonesample.R, "Rank biserial is consistent with rcompanion", jasp-issues #1158).
JASP_PROPORTIONS = np.array([0, 1 / 3, 1 / 2, 3 / 7, 1 / 4, 1 / 4, 1 / 2, 0, 0, 1 / 5, 3 / 7, 3 / 4, 1, 1, 3 / 4, 0,
                             1, 1])


def reacttime_long() -> pd.DataFrame:
    """REACTTIME in long form: subject, noise (absent, present), deg (0, 4, 8), rt."""
    rows = [{"subject": s + 1, "noise": noise, "deg": deg, "rt": REACTTIME[s, j * 3 + k]}
            for s in range(len(REACTTIME)) for j, noise in enumerate(("absent", "present"))
            for k, deg in enumerate(("0", "4", "8"))]
    return pd.DataFrame(rows)


def agrees(actual: float, printed: str) -> bool:
    """Whether ``actual`` rounds to the published ``printed`` value at the precision printed
    (``"0.9616"``, ``"2.0868e-07"``, ``"40.719"``)."""
    if "e" in printed.lower():
        mantissa, _exponent = printed.lower().split("e")
        digits = len(mantissa.replace("-", "").replace(".", "").lstrip("0"))
        return f"{actual:.{digits - 1}e}" == f"{float(printed):.{digits - 1}e}"
    decimals = len(printed.split(".")[1]) if "." in printed else 0
    return round(actual, decimals) == float(printed)


# O'Brien & Kaiser (1985), "MANOVA method for analyzing repeated measures designs", Psychological Bulletin 97(2),
# Table 7: 16 subjects, treatment between (control, A, B) × phase (pre, post, fup) × hour (1-5) within, columns
# pre.1 … pre.5, post.1 … post.5, fup.1 … fup.5 (R's carData::OBrienKaiser; afex's obk.long in long form). The
# reference values of afex and emmeans for it are in tests/analysis/reference/afex_emmeans.csv.
OBRIEN_KAISER_TREATMENT = ("control",) * 5 + ("A",) * 4 + ("B",) * 7
OBRIEN_KAISER = np.array([
    [1, 2, 4, 2, 1, 3, 2, 5, 3, 2, 2, 3, 2, 4, 4],
    [4, 4, 5, 3, 4, 2, 2, 3, 5, 3, 4, 5, 6, 4, 1],
    [5, 6, 5, 7, 7, 4, 5, 7, 5, 4, 7, 6, 9, 7, 6],
    [5, 4, 7, 5, 4, 2, 2, 3, 5, 3, 4, 4, 5, 3, 4],
    [3, 4, 6, 4, 3, 6, 7, 8, 6, 3, 4, 3, 6, 4, 3],
    [7, 8, 7, 9, 9, 9, 9, 10, 8, 9, 9, 10, 11, 9, 6],
    [5, 5, 6, 4, 5, 7, 7, 8, 10, 8, 8, 9, 11, 9, 8],
    [2, 3, 5, 3, 2, 2, 4, 8, 6, 5, 6, 6, 7, 5, 6],
    [3, 3, 4, 6, 4, 4, 5, 6, 4, 1, 5, 4, 7, 5, 4],
    [4, 4, 5, 3, 4, 6, 7, 6, 8, 8, 8, 8, 9, 7, 8],
    [3, 3, 4, 2, 3, 5, 4, 7, 5, 4, 5, 6, 8, 6, 5],
    [6, 7, 8, 6, 3, 9, 10, 11, 9, 6, 8, 7, 10, 8, 7],
    [5, 5, 6, 8, 6, 4, 6, 6, 8, 6, 7, 7, 8, 10, 8],
    [2, 2, 3, 1, 2, 5, 6, 7, 5, 2, 6, 7, 8, 6, 3],
    [2, 2, 3, 4, 4, 6, 6, 7, 9, 7, 7, 7, 8, 6, 7],
    [4, 5, 7, 5, 4, 7, 7, 8, 6, 7, 7, 8, 10, 8, 7],
], dtype=float)


def obrien_kaiser_long() -> pd.DataFrame:
    """OBRIEN_KAISER in long form: id, treatment, phase, hour (``"1"`` … ``"5"``), value."""
    rows = [{"id": f"s{s + 1}", "treatment": OBRIEN_KAISER_TREATMENT[s], "phase": phase, "hour": str(hour + 1),
             "value": OBRIEN_KAISER[s, p * 5 + hour]}
            for s in range(len(OBRIEN_KAISER)) for p, phase in enumerate(("pre", "post", "fup")) for hour in range(5)]
    return pd.DataFrame(rows)


def to_digits(actual: float, reference: float, digits: int = 4) -> bool:
    """Whether ``actual`` agrees with ``reference`` to ``digits`` significant digits: within half a unit of the
    reference's ``digits``-th significant digit. A reference below 1e-10 in size is a zero written with rounding
    error (e.g. −4.4e-16 for a difference of equal means), and agrees with anything that small."""
    if abs(reference) < 1e-10:
        return bool(abs(actual) < 1e-10)
    unit = 10.0 ** (np.floor(np.log10(abs(reference))) - (digits - 1))
    return bool(abs(actual - reference) <= unit / 2)
