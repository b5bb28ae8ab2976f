"""Two-way repeated-measures ANOVA and simple main effects: a thin adapter over pingouin.

For subjects s = 1..n crossed with the levels of within factors A (a levels) and B (b levels),
each effect is tested against its own subject-by-effect error term:

    F_A  = (SS_A / (a-1))          / (SS_AxS  / ((a-1)(n-1)))
    F_B  = (SS_B / (b-1))          / (SS_BxS  / ((b-1)(n-1)))
    F_AB = (SS_AB / ((a-1)(b-1)))  / (SS_ABxS / ((a-1)(b-1)(n-1)))

(Maxwell & Delaney, *Designing Experiments and Analyzing Data*, ch. 12). Effect sizes:

* generalized eta squared (Olejnik & Algina 2003; Bakeman 2005, Table 1), for designs whose factors
  are all manipulated and within-subject:
  ``ges = SS_effect / (SS_effect + SS_S + SS_AxS + SS_BxS + SS_ABxS)``; pingouin's ``ng2`` is
  exactly this in its two-way within function and ``SS_A / (SS_A + SS_S + SS_AxS)`` in the one-way
  case (pingouin issue #251), which is what R's ``ez``/``afex`` report as ``ges``;
* partial eta squared ``SS_effect / (SS_effect + SS_error)``, which, with
  ``F = (SS_effect/df1) / (SS_error/df2)``, equals ``F·df1 / (F·df1 + df2)``.

The ``p`` values are the uncorrected ones: with two-level factors (the robot × kitchen study)
sphericity holds trivially. Simple main effects are separate one-way RM-ANOVAs of one factor within
each level of the other (own error term per level), Holm-adjusted across the levels
(Holm 1979).
"""

from __future__ import annotations

from collections.abc import Sequence

import pandas as pd

from analysis.cells import factor_levels, require_complete
from analysis.errors import AnalysisInputError

ANOVA_COLUMNS = ["effect", "df1", "df2", "SS", "MS", "F", "p", "ges", "partial_eta2"]
SIMPLE_EFFECT_COLUMNS = ["level", "effect", "df1", "df2", "F", "p", "p_holm", "ges"]


def rm_anova_2way(
    df: pd.DataFrame, dv: str, within: Sequence[str], subject: str
) -> pd.DataFrame:
    """Two-way repeated-measures ANOVA of ``dv`` on ``within = [A, B]``.

    ``df`` is long: one row per subject and cell, with every subject in every cell (see
    ``analysis.cells.complete_cases``). Returns one row per effect (``A``, ``B``, ``A * B``) with
    columns ``effect, df1, df2, SS, MS, F, p, ges, partial_eta2``; the degrees of freedom come from
    the data (``df1 = a-1``, ``df2 = (a-1)(n-1)`` and so on).
    """
    factors = _two_factors(within)
    require_complete(df, dv, factors, subject)
    import pingouin as pg

    aov = pg.rm_anova(
        data=df, dv=dv, within=factors, subject=subject, detailed=True, effsize="ng2"
    )
    out = pd.DataFrame(
        {
            "effect": aov["Source"].astype(str),
            "df1": aov["ddof1"].astype(int),
            "df2": aov["ddof2"].astype(int),
            "SS": aov["SS"].astype(float),
            "MS": aov["MS"].astype(float),
            "F": aov["F"].astype(float),
            "p": aov["p_unc"].astype(float),
            "ges": aov["ng2"].astype(float),
        }
    )
    out["partial_eta2"] = _partial_eta2(out["F"], out["df1"], out["df2"])
    return out[ANOVA_COLUMNS].reset_index(drop=True)


def simple_main_effects(
    df: pd.DataFrame, dv: str, factor: str, by: str, subject: str
) -> pd.DataFrame:
    """One-way RM-ANOVA of ``factor`` within each level of ``by``, Holm-adjusted across levels.

    Returns one row per level of ``by`` with columns ``level, effect, df1, df2, F, p, p_holm, ges``
    (``effect`` is the name of ``factor``; ``ges`` is the one-way generalized eta squared).
    """
    factors = _two_factors([factor, by])
    require_complete(df, dv, factors, subject)
    import pingouin as pg

    rows = []
    for level in factor_levels(df, by):
        part = df[df[by] == level]
        aov = pg.rm_anova(
            data=part, dv=dv, within=factor, subject=subject, correction=False, effsize="ng2"
        )
        rows.append(
            {
                "level": level,
                "effect": factor,
                "df1": int(aov.at[0, "ddof1"]),
                "df2": int(aov.at[0, "ddof2"]),
                "F": float(aov.at[0, "F"]),
                "p": float(aov.at[0, "p_unc"]),
                "ges": float(aov.at[0, "ng2"]),
            }
        )
    out = pd.DataFrame(rows)
    out["p_holm"] = holm(out["p"])
    return out[SIMPLE_EFFECT_COLUMNS]


def holm(pvalues: pd.Series) -> pd.Series:
    """Holm (1979) step-down adjustment: ``p_(i) -> max_{j<=i} min(1, (m-j+1)·p_(j))``.

    NaN p values (an effect without error variance) are left out of ``m`` and stay NaN.
    """
    import pingouin as pg

    _, adjusted = pg.multicomp(pvalues.to_numpy(dtype=float), method="holm")
    return pd.Series(adjusted, index=pvalues.index, name="p_holm")


def _partial_eta2(f: pd.Series, df1: pd.Series, df2: pd.Series) -> pd.Series:
    """``SS_effect / (SS_effect + SS_error)`` written as ``F·df1 / (F·df1 + df2)``."""
    return (f * df1) / (f * df1 + df2)


def _two_factors(within: Sequence[str]) -> list[str]:
    factors = list(within)
    if len(factors) != 2 or factors[0] == factors[1]:
        raise AnalysisInputError(
            f"a two-way design needs exactly two distinct within factors, got {factors}"
        )
    return factors
