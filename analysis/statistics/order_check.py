"""Order and carry-over: does a measure drift with the trial's position in the participant's sequence?

A linear mixed model (statsmodels ``MixedLM``, REML) with a random intercept per participant, the full factorial
of the within factors as fixed effects and the trial's position (1 = first main trial) as a linear covariate:

    y = conditions + β · position + u_participant + e.

β is the change per later position (practice or fatigue); its Wald z test says whether an order effect was
found (α = .05). Carry-over that differs between conditions (asymmetric transfer) shows as a position ×
factor interaction: a second model adds those interactions and a likelihood-ratio test (ML fits) compares the
two. With counterbalanced orders the condition effects are estimated free of a linear position trend either
way; the check says whether one was there. Effects of one specific preceding condition are not modelled.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import pandas as pd
from scipy import stats

from analysis.statistics.apa import format_p, format_signed

ORDER_COLUMNS = ["measure", "n", "positions", "slope", "se", "z", "p", "order_effect", "carryover_chi2",
                 "carryover_df", "carryover_p", "sentence", "note"]
ALPHA = 0.05


@dataclass(frozen=True, slots=True)
class OrderCheck:
    measure: str
    n: int
    positions: int
    slope: float = math.nan
    se: float = math.nan
    z: float = math.nan
    p: float = math.nan
    carryover_chi2: float = math.nan
    carryover_df: int = 0
    carryover_p: float = math.nan
    note: str = ""

    @property
    def order_effect(self) -> bool | None:
        return None if math.isnan(self.p) else self.p < ALPHA

    @property
    def sentence(self) -> str:
        """The plain-words verdict for the report."""
        if self.order_effect is None:
            return f"Order was not checked for {self.measure}: {self.note}."
        found = "An order effect was found" if self.order_effect else "No order effect was found"
        text = (f"{found} for {self.measure}: each later position changed it by {format_signed(self.slope)} "
                f"(SE {format_signed(self.se)}, z = {self.z:.2f}, p {_p(self.p)}).")
        if not math.isnan(self.carryover_p):
            differs = "differed" if self.carryover_p < ALPHA else "did not differ detectably"
            text += (f" The condition effects {differs} between early and late positions (position × factor, "
                     f"χ²({self.carryover_df}) = {self.carryover_chi2:.2f}, p {_p(self.carryover_p)})"
                     + (": possible carry-over." if self.carryover_p < ALPHA else "."))
        if self.note:
            text += f" Note: {self.note}."
        return text

    def row(self) -> dict[str, object]:
        return {**{c: getattr(self, c) for c in ORDER_COLUMNS if c not in ("sentence", "order_effect")},
                "order_effect": self.order_effect, "sentence": self.sentence}


def order_check(df: pd.DataFrame, dv: str, within: Sequence[str], subject: str, position: str = "position"
                ) -> OrderCheck:
    """Fit the models above on the complete-case table ``df`` (one row per participant and cell)."""
    n = int(df[subject].nunique())
    if position not in df.columns:
        return OrderCheck(dv, n, 0, note=f"the table has no {position!r} column")
    data = df[[subject, *within, position, dv]].dropna().copy()
    positions = int(data[position].nunique())
    if positions < 2 or n < 3:
        return OrderCheck(dv, n, positions, note="fewer than 3 participants or 2 positions")
    if data[dv].nunique() < 2:
        return OrderCheck(dv, n, positions, note="the measure does not vary")
    confounded = _confounding(data, within, position)
    if confounded:
        return OrderCheck(dv, n, positions, note=confounded)
    names = {col: f"f{i}" for i, col in enumerate(within)}
    data = data.rename(columns={**names, dv: "y", position: "pos", subject: "subject"})
    data["y"] = data["y"].astype(float)
    conditions = " * ".join(f"C({n_})" for n_ in names.values())
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            base = _fit(f"y ~ {conditions} + pos", data, reml=True)
            slope, se = float(base.params["pos"]), float(base.bse["pos"])
            lr = _carryover(data, conditions, list(names.values()))
    except (ValueError, ArithmeticError, IndexError, KeyError) as exc:
        return OrderCheck(dv, n, positions, note=f"the model could not be fitted ({exc})")
    if not (math.isfinite(slope) and math.isfinite(se) and se > 0):
        return OrderCheck(dv, n, positions, note="the model could not estimate the position effect")
    z = slope / se
    return OrderCheck(dv, n, positions, slope, se, z, float(2 * stats.norm.sf(abs(z))), *lr,
                      note=_fit_note([str(w.message) for w in caught]))


def _confounding(data: pd.DataFrame, within: Sequence[str], position: str) -> str:
    """Why position cannot be separated from condition, or empty: when every condition was always played at one
    position (all participants in one order), position is a function of condition. This is exactly when position
    is a linear combination of the conditions' full-factorial columns (they span the cell indicators), so the
    models below are never fitted on a design whose position column is redundant."""
    per_condition = data.groupby(list(within), observed=True)[position].nunique()
    if (per_condition <= 1).all():
        return ("position is confounded with condition: every condition was played at the same position by every "
                "participant (one order for all), so an order effect cannot be told apart from the condition "
                "effects; counterbalance the order")
    return ""


def _fit(formula: str, data: pd.DataFrame, reml: bool) -> Any:
    import statsmodels.formula.api as smf

    return smf.mixedlm(formula, data, groups=data["subject"]).fit(reml=reml)


def _carryover(data: pd.DataFrame, conditions: str, factors: list[str]) -> tuple[float, int, float]:
    """Likelihood-ratio test of the position × factor interactions (ML fits)."""
    small = _fit(f"y ~ {conditions} + pos", data, reml=False)
    big = _fit(f"y ~ {conditions} + pos + " + " + ".join(f"pos:C({f})" for f in factors), data, reml=False)
    extra = len(big.params) - len(small.params)
    chi2 = 2 * (float(big.llf) - float(small.llf))
    if extra <= 0 or not math.isfinite(chi2):
        return (math.nan, 0, math.nan)
    chi2 = max(chi2, 0.0)
    return (chi2, extra, float(stats.chi2.sf(chi2, extra)))


def _fit_note(messages: list[str]) -> str:
    """What statsmodels' warnings mean for the reader, in one phrase each."""
    notes = []
    if any("boundary" in m for m in messages):
        notes.append("the participants' random-intercept variance was estimated at 0")
    if any("converge" in m or "optimization failed" in m.lower() for m in messages):
        notes.append("the mixed model's optimiser did not converge cleanly, so read this check with care")
    return "; ".join(notes)


def _p(p: float) -> str:
    text = format_p(p)
    return text if text[0] in "<>" else f"= {text}"
