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
