"""Repeated-measures ANOVA for one, two or three within factors, with sphericity corrections.

Each effect E (every main effect and interaction of the within factors) is tested against its own
subject × effect error term. With the effect's contrast scores z_s (d = df1 columns, see
:mod:`analysis.statistics.sphericity`) of the n participants and their mean z̄:

    SS_E = n ‖z̄‖²,   SS_error = Σ_s ‖z_s − z̄‖²,   F = (SS_E / d) / (SS_error / (d (n − 1)))  on (d, d(n − 1)) df,

the classic univariate sums of squares written in their contrast form (Maxwell & Delaney 2004, ch. 12–14).
pingouin's ``rm_anova`` covers one and two factors and statsmodels' ``AnovaRM`` has neither sums of squares nor
sphericity, and the platform accepts three factors, so the table is computed here for every design; the tests
check it against both and against R's published outputs. ``MSE`` is the error mean square SS_error / df2.

Effect sizes: generalized η² for designs whose factors are all manipulated within subjects (Olejnik & Algina
2003; Bakeman 2005, Table 1), ``ges = SS_E / (SS_E + SS_subjects + Σ every effect's SS_error)``, which R's
``afex``/``ez`` report as ``ges``; partial η² = SS_E / (SS_E + SS_error). Their intervals: see
:mod:`analysis.statistics.effect_sizes`.

Sphericity: for an effect with d > 1 the table has Mauchly's W, χ², df and p and the Greenhouse–Geisser and
Huynh–Feldt ε with the corrected df (df × ε) and p. Which p to read (``correction``, ``df1_read``,
``df2_read``, ``p_read``; the rule is written in docs/analysis.md "Which p to read"): an effect with one df is
spherical, read the uncorrected test; otherwise read the Greenhouse–Geisser test when ε_GG ≤ 0.75 and the
Huynh–Feldt test (ε = min(ε_HF, 1)) when ε_GG > 0.75 (Huynh & Feldt 1976; Girden 1992), whatever Mauchly's
test says (it has little power in small samples).

An effect that cannot be tested (no variance, no error variance, fewer than two participants) gets NaN
statistics and a ``note`` saying why; the other effects are computed as usual.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence

import numpy as np
import pandas as pd
from scipy import stats

from analysis.preparation.cells import factor_levels, wide_matrix
from analysis.statistics.effect_sizes import BOOTSTRAP_RESAMPLES, partial_eta2_ci, percentile_interval, resample_indices
from analysis.statistics.sphericity import Sphericity, effect_contrasts, sphericity

ANOVA_COLUMNS = [
    "effect", "df1", "df2", "SS", "SS_error", "MS", "MSE", "F", "p", "ges", "partial_eta2",
    "partial_eta2_ci_low", "partial_eta2_ci_high", "mauchly_W", "mauchly_chi2", "mauchly_df", "mauchly_p",
    "eps_gg", "eps_hf", "df1_gg", "df2_gg", "p_gg", "df1_hf", "df2_hf", "p_hf",
    "correction", "df1_read", "df2_read", "p_read", "note",
]
GG_THRESHOLD = 0.75
"""ε_GG above which the Huynh–Feldt correction is read (Huynh & Feldt 1976; Girden 1992)."""


def effects_of(within: Sequence[str]) -> list[tuple[int, ...]]:
    """Factor positions of every effect: main effects first, then two-way, then three-way interactions."""
    k = len(within)
    return [combo for size in range(1, k + 1) for combo in itertools.combinations(range(k), size)]


def effect_name(within: Sequence[str], effect: Sequence[int]) -> str:
    """``robot``, ``robot * kitchen``."""
    return " * ".join(within[f] for f in effect)


def rm_anova(df: pd.DataFrame, dv: str, within: Sequence[str], subject: str) -> pd.DataFrame:
    """One row per effect with the columns ``ANOVA_COLUMNS``; ``df`` is complete (one value per subject and cell,
    see :func:`analysis.preparation.cells.complete_cases`)."""
    within = list(within)
    values, _ = wide_matrix(df, dv, within, subject)
    levels = [len(factor_levels(df, f)) for f in within]
    return anova_table(values, levels, within)


def anova_table(values: np.ndarray, levels: Sequence[int], within: Sequence[str]) -> pd.DataFrame:
    """The ANOVA of the n × C matrix ``values`` (cells in design order, ``levels[f]`` levels per factor)."""
    n, n_cells = values.shape
    effects = effects_of(within)
    sums = [effect_sums(values, levels, e) for e in effects]
    ss_subjects = effect_sums(values, levels, ())[1]
    error_total = ss_subjects + sum(err for _, err, _ in sums)
    total = float(((values - values.mean()) ** 2).sum())
    rows = []
    for effect, (ss, ss_err, scores) in zip(effects, sums, strict=True):
        d = scores.shape[1]
        row = _effect_row(effect_name(within, effect), n, d, ss, ss_err, total, error_total)
        row.update(_sphericity_columns(row, sphericity(scores, n_cells)))
        rows.append(row)
    return pd.DataFrame(rows, columns=ANOVA_COLUMNS)


def effect_sums(values: np.ndarray, levels: Sequence[int], effect: Sequence[int]) -> tuple[float, float, np.ndarray]:
    """``(SS_E, SS_error, scores)`` of one effect; the empty effect gives the subjects' sum of squares as
    SS_error."""
    scores = values @ effect_contrasts(levels, effect)
    mean = scores.mean(axis=0)
    return float(len(values) * (mean**2).sum()), float(((scores - mean) ** 2).sum()), scores


def corrected_p(f_value: float, df1: float, df2: float, eps: float) -> float:
    """p of F on (ε·df1, ε·df2) degrees of freedom."""
    if not (math.isfinite(f_value) and math.isfinite(eps)):
        return math.nan
    return float(stats.f.sf(f_value, df1 * eps, df2 * eps))


def reading(d: int, eps_gg: float, eps_hf: float) -> str:
    """Which test to read: ``none`` (one df), ``GG`` or ``HF`` (see the module docstring)."""
    if d == 1 or not math.isfinite(eps_gg):
        return "none"
    return "GG" if eps_gg <= GG_THRESHOLD or not math.isfinite(eps_hf) else "HF"


def _effect_row(name: str, n: int, d: int, ss: float, ss_err: float, total: float,
                error_total: float) -> dict[str, object]:
    df1, df2 = d, d * (n - 1)
    note = _untestable(n, ss, ss_err, total)
    f_value = math.nan if note else (ss / df1) / (ss_err / df2)
    p = math.nan if note else float(stats.f.sf(f_value, df1, df2))
    low, high = partial_eta2_ci(f_value, df1, df2)
    return {
        "effect": name, "df1": df1, "df2": df2, "SS": ss, "SS_error": ss_err, "MS": ss / df1,
        "MSE": ss_err / df2 if df2 else math.nan, "F": f_value, "p": p,
        "ges": ss / (ss + error_total) if ss + error_total > 0 else math.nan,
        "partial_eta2": ss / (ss + ss_err) if ss + ss_err > 0 else math.nan,
        "partial_eta2_ci_low": low, "partial_eta2_ci_high": high, "note": note,
    }


def _untestable(n: int, ss: float, ss_err: float, total: float) -> str:
    tiny = 1e-12 * max(total, 1.0)
    if n < 2:
        return "not testable: fewer than 2 participants"
    if total <= tiny:
        return "not testable: no variance (every value is the same)"
    if ss_err <= tiny:
        return ("not testable: no variance in this effect" if ss <= tiny else
                "not testable: no error variance (every participant shows the same pattern), so F is undefined")
    return ""


def _sphericity_columns(row: dict[str, object], s: Sphericity) -> dict[str, object]:
    f_value, df1, df2 = float(row["F"]), float(row["df1"]), float(row["df2"])  # type: ignore[arg-type]
    hf = min(s.eps_hf, 1.0) if math.isfinite(s.eps_hf) else math.nan
    correction = reading(s.d, s.eps_gg, s.eps_hf) if not row["note"] else "none"
    eps_read = {"none": 1.0, "GG": s.eps_gg, "HF": hf}[correction]
    note = str(row["note"])
    if s.note and s.d > 1 and not note:
        note = f"sphericity: {s.note}"
    return {
        "mauchly_W": s.w, "mauchly_chi2": s.chi2, "mauchly_df": s.df, "mauchly_p": s.p,
        "eps_gg": s.eps_gg, "eps_hf": s.eps_hf,
        "df1_gg": df1 * s.eps_gg, "df2_gg": df2 * s.eps_gg, "p_gg": corrected_p(f_value, df1, df2, s.eps_gg),
        "df1_hf": df1 * hf, "df2_hf": df2 * hf, "p_hf": corrected_p(f_value, df1, df2, hf),
        "correction": correction, "df1_read": df1 * eps_read, "df2_read": df2 * eps_read,
        "p_read": corrected_p(f_value, df1, df2, eps_read), "note": note,
    }


def ges_bootstrap(values: np.ndarray, levels: Sequence[int], within: Sequence[str], rng: np.random.Generator,
                  resamples: int = BOOTSTRAP_RESAMPLES) -> list[tuple[float, float]]:
    """Percentile intervals (level ``ETA_CI_LEVEL``) of each effect's generalized η², from ``resamples``
    resamples of the participants drawn with ``rng`` (see :mod:`analysis.statistics.effect_sizes`)."""
    n = len(values)
    picks = resample_indices(n, rng, resamples)

    def sums(effect: Sequence[int]) -> tuple[np.ndarray, np.ndarray]:
        scores = (values @ effect_contrasts(levels, effect))[picks]
        mean = scores.mean(axis=1)
        return n * (mean**2).sum(axis=1), ((scores - mean[:, None, :]) ** 2).sum(axis=(1, 2))

    per_effect = [sums(e) for e in effects_of(within)]
    error_total = sums(())[1] + sum(err for _, err in per_effect)
    with np.errstate(divide="ignore", invalid="ignore"):
        return [percentile_interval(ss / (ss + error_total)) for ss, _ in per_effect]
