"""Models beside the ANOVA: a linear mixed model for unbalanced or incomplete data (``analyze --model lmm``), and a
count model for the interrupts.

* Linear mixed model (statsmodels ``MixedLM``, REML): the full factorial of the factors (between and within) in
  sum-to-zero coding as fixed effects, a random intercept per participant, fitted on every row with a value (no
  complete-case rule: a participant missing a cell still counts with the others). Each term (main effect,
  interaction) is tested with a Wald χ² on its coefficients (``wald_test_terms``). The formula is printed and
  written, in lme4's notation: ``ticks ~ robot * kitchen + (1 | participant)``.
* Count model (``interrupts``, a count per trial): a Poisson GEE (generalized estimating equations; statsmodels
  ``GEE``, log link, exchangeable working correlation within participant, robust standard errors), the same fixed
  effects, Wald χ² per term, and the rate ratio of each coefficient. Overdispersion does not bias a GEE's tests:
  its sandwich errors absorb it (Liang & Zeger 1986).

Rows (``lmm.csv`` / ``count_model.csv``): measure, model, formula, term, chi2, df, p, n_obs, n_subjects, note.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from typing import Any

import pandas as pd

MODEL_COLUMNS = ["measure", "model", "formula", "term", "chi2", "df", "p", "n_obs", "n_subjects", "note"]
COUNT_MEASURES = ("interrupts",)
LMM = "linear mixed model (REML, random intercept)"
GEE = "Poisson GEE (log link, exchangeable, robust SE)"


def written_formula(dv: str, factors: Sequence[str], subject: str | None) -> str:
    """``ticks ~ robot * kitchen + (1 | participant)`` (no random part for the GEE)."""
    random = f" + (1 | {subject})" if subject else ""
    return f"{dv} ~ {' * '.join(factors)}{random}"


def _prepared(df: pd.DataFrame, dv: str, factors: Sequence[str],
              subject: str) -> tuple[pd.DataFrame, str, dict[str, str]]:
    names = {f: f"f{i}" for i, f in enumerate(factors)}
    data = df[[subject, *factors, dv]].dropna().rename(columns={**names, dv: "y", subject: "subject"})
    data["y"] = pd.to_numeric(data["y"], errors="coerce").astype(float)
    for f in names.values():
        data[f] = data[f].astype(str)
    fixed = " * ".join(f"C({n}, Sum)" for n in names.values())
    back = {f"C({n}, Sum)": f for f, n in names.items()}
    return data, f"y ~ {fixed}", back


def _term_rows(result: Any, back: dict[str, str], base: dict[str, object]) -> list[dict[str, object]]:
    frame = result.wald_test_terms(skip_single=False, scalar=True).summary_frame()
    rows = []
    for term, row in frame.iterrows():
        if term == "Intercept":
            continue
        name = " * ".join(back.get(part, part) for part in str(term).split(":"))
        rows.append({**base, "term": name, "chi2": float(row["chi2"]), "df": int(row["df constraint"]),
                     "p": float(row["P>chi2"]), "note": base.get("note", "")})
    return rows


def _failed(base: dict[str, object], reason: str) -> list[dict[str, object]]:
    return [{**base, "term": "", "chi2": math.nan, "df": math.nan, "p": math.nan, "note": f"not fitted: {reason}"}]


def lmm_tests(df: pd.DataFrame, dv: str, factors: Sequence[str], subject: str) -> list[dict[str, object]]:
    """The linear mixed model's Wald test per term (rows of :data:`MODEL_COLUMNS`)."""
    import statsmodels.formula.api as smf

    data, formula, back = _prepared(df, dv, factors, subject)
    base: dict[str, object] = {"measure": dv, "model": LMM, "formula": written_formula(dv, factors, subject),
                               "n_obs": len(data), "n_subjects": int(data["subject"].nunique()), "note": ""}
    if data["y"].nunique() < 2 or data["subject"].nunique() < 2:
        return _failed(base, "the measure does not vary or there are fewer than 2 participants")
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            result = smf.mixedlm(formula, data, groups=data["subject"]).fit(reml=True)
            rows = _term_rows(result, back, base)
    except (ValueError, ArithmeticError, IndexError, KeyError) as exc:
        return _failed(base, str(exc))
    if any("converge" in str(w.message).lower() for w in caught):
        rows = [{**r, "note": "the optimiser did not converge cleanly: read with care"} for r in rows]
    return rows


def count_tests(df: pd.DataFrame, dv: str, factors: Sequence[str], subject: str) -> list[dict[str, object]]:
    """The Poisson GEE's Wald test per term, and its rate ratios in the note."""
    import numpy as np
    import statsmodels.api as sm
    import statsmodels.formula.api as smf

    data, formula, back = _prepared(df, dv, factors, subject)
    base: dict[str, object] = {"measure": dv, "model": GEE, "formula": written_formula(dv, factors, None),
                               "n_obs": len(data), "n_subjects": int(data["subject"].nunique()), "note": ""}
    if (data["y"] < 0).any() or not np.all(np.mod(data["y"], 1) == 0):
        return _failed(base, "the measure is not a count (whole numbers ≥ 0)")
    if data["y"].nunique() < 2 or data["subject"].nunique() < 2:
        return _failed(base, "the measure does not vary or there are fewer than 2 participants")
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            result = smf.gee(formula, groups="subject", data=data, family=sm.families.Poisson(),
                             cov_struct=sm.cov_struct.Exchangeable()).fit()
            rows = _term_rows(result, back, base)
    except (ValueError, ArithmeticError, IndexError, KeyError) as exc:
        return _failed(base, str(exc))
    return rows


def model_sentence(row: pd.Series) -> str:
    """``robot: χ²(1) = 4.20, p = .040`` of one term (or why the model was not fitted)."""
    from analysis.statistics.apa import p_clause

    if not row["term"]:
        return str(row["note"])
    return f"{row['term']}: χ²({int(row['df'])}) = {float(row['chi2']):.2f}, {p_clause(float(row['p']))}"
