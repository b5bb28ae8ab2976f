"""The report's tables, built from the result frames: numbers formatted once, here."""

from __future__ import annotations

import math
from collections.abc import Sequence

import pandas as pd

from analysis.reporting.document import Block, table
from analysis.statistics.apa import format_df, format_p, format_proportion

READ = {"none": "uncorrected", "GG": "Greenhouse–Geisser", "HF": "Huynh–Feldt"}


def number(value: object, digits: int | None = None) -> str:
    """Fixed decimals: 2 for magnitudes of 10 and more, else 3, unless ``digits`` is given; ``n/a`` for NaN."""
    try:
        x = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        return "n/a"
    if math.isnan(x):
        return "n/a"
    if digits is None:
        digits = 2 if abs(x) >= 10 else 3
    return f"{x:.{digits}f}"


def interval(low: object, high: object, proportion: bool = False, digits: int | None = None) -> str:
    """``[.21, .52]`` (proportions) or ``[1.234, 5.678]``; empty when unknown."""
    if pd.isna(low) or pd.isna(high):
        return ""
    if proportion:
        return f"[{format_proportion(float(low), 2)}, {format_proportion(float(high), 2)}]"  # type: ignore[arg-type]
    return f"[{number(low, digits)}, {number(high, digits)}]"


def anova_table(anova: pd.DataFrame) -> Block:
    """Uncorrected and corrected tests, the error term, which test to read and the effect sizes."""
    columns = ("effect", "df1", "df2", "MSE", "F", "p", "ε GG", "p GG", "ε HF", "p HF", "read", "η²G [90% CI]",
               "η²p [90% CI]")
    rows = [(
        str(r["effect"]), format_df(float(r["df1"])), format_df(float(r["df2"])), number(r["MSE"]),
        number(r["F"], 2), format_p(float(r["p"])), *_corrected(r), READ.get(str(r["correction"]), ""),
        f"{format_proportion(float(r['ges']), 3)} {interval(r['ges_ci_low'], r['ges_ci_high'], True)}".strip(),
        f"{format_proportion(float(r['partial_eta2']), 3)} "
        f"{interval(r['partial_eta2_ci_low'], r['partial_eta2_ci_high'], True)}".strip(),
    ) for _, r in anova.iterrows()]
    return table(columns, rows)


def sphericity_table(anova: pd.DataFrame) -> Block | None:
    """Mauchly's test for the effects with more than one df, or ``None`` when there is none."""
    rows = [(str(r["effect"]), number(r["mauchly_W"]), number(r["mauchly_chi2"], 2), format_df(float(r["mauchly_df"]))
             if not pd.isna(r["mauchly_df"]) else "n/a", format_p(float(r["mauchly_p"])),
             number(r["eps_gg"]), number(r["eps_hf"]))
            for _, r in anova.iterrows() if int(r["df1"]) > 1]
    return table(("effect", "Mauchly's W", "χ²", "df", "p", "ε GG", "ε HF"), rows) if rows else None


def simple_table(simple: pd.DataFrame) -> Block:
    columns = ("effect of", "at", "df", "MSE", "F", "p", "p (Holm)", "read", "η²G", "difference [95% CI]",
               "d_z [95% CI]")
    rows = [(str(r["factor"]), str(r["at"]), f"{format_df(float(r['df1_read']))}, {format_df(float(r['df2_read']))}",
             number(r["MSE"]), number(r["F"], 2), format_p(float(r["p_read"])), format_p(float(r["p_holm"])),
             READ.get(str(r["correction"]), ""), format_proportion(float(r["ges"]), 3), *_difference(r))
            for _, r in simple.iterrows()]
    return table(columns, rows)


def pairwise_table(pairwise: pd.DataFrame) -> Block:
    columns = ("factor", "at", "comparison", "mean difference [95% CI]", "t", "df", "p", "p (Holm)",
               "d_z [95% CI]")
    rows = [(str(r["factor"]), str(r["at"]) if r["at"] else "averaged", f"{r['level_1']} − {r['level_2']}",
             f"{number(r['mean_diff'])} {interval(r['ci95_low'], r['ci95_high'])}".strip(), number(r["t"], 2),
             format_df(float(r["df"])), format_p(float(r["p"])), format_p(float(r["p_holm"])),
             f"{number(r['dz'], 2)} {interval(r['dz_ci_low'], r['dz_ci_high'], digits=2)}".strip())
            for _, r in pairwise.iterrows()]
    return table(columns, rows)


def _difference(r: pd.Series) -> tuple[str, str]:
    """``level_1 − level_2: mean difference [CI]`` and ``d_z [CI]`` of a two-level simple effect (else empty)."""
    if pd.isna(r.get("mean_diff")):
        return ("", "")
    return (f"{r['level_1']} − {r['level_2']}: {number(r['mean_diff'])} {interval(r['ci95_low'], r['ci95_high'])}",
            f"{number(r['dz'], 2)} {interval(r['dz_ci_low'], r['dz_ci_high'], digits=2)}".strip())


def rank_table(ranks: pd.DataFrame) -> Block:
    columns = ("factor", "test", "levels", "n", "statistic", "df", "p", "effect size")
    rows = [(str(r["factor"]), str(r["test"]), str(r["levels"]), str(int(r["n"])), number(r["statistic"], 2),
             "" if pd.isna(r["df"]) else format_df(float(r["df"])), format_p(float(r["p"])),
             f"{r['effect_size_name']} = {number(r['effect_size'], 2)}") for _, r in ranks.iterrows()]
    return table(columns, rows)


def descriptives_table(desc: pd.DataFrame, within: Sequence[str]) -> Block:
    columns = (*within, "n", "mean", "sd", "se (within)", "95% CI (within)")
    rows = [(*(str(r[f]) for f in within), str(int(r["n"])), number(r["mean"]), number(r["sd"]), number(r["se_ws"]),
             interval(r["ci95_low"], r["ci95_high"])) for _, r in desc.iterrows()]
    return table(columns, rows)


def _corrected(r: pd.Series) -> tuple[str, str, str, str]:
    if int(r["df1"]) == 1:
        return ("", "", "", "")
    return (number(r["eps_gg"]), format_p(float(r["p_gg"])), number(r["eps_hf"]), format_p(float(r["p_hf"])))
