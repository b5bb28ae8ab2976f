"""The order of each within factor's levels: the study's order, never the alphabet.

Tables, plots and follow-ups list levels in one order per factor, carried as an ordered pandas categorical:

* a stored study: the order of the study file (``robots``, ``kitchens``, ``views``; see
  :mod:`analysis.source.study_design`);
* a CSV (``analyze --csv``): the order in which the levels first appear in the file, unless
  ``--levels factor=a,b,c`` gives it.

A given order must name every level present in the data (a typo would otherwise silently reorder a plot);
levels it names that the data lack are dropped, as they have no cell.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import pandas as pd

from analysis.source.input_errors import AnalysisInputError

LevelOrder = Mapping[str, Sequence[str]]


def apply_level_order(df: pd.DataFrame, within: Sequence[str], given: LevelOrder | None = None,
                      strict: bool = True) -> pd.DataFrame:
    """A copy of ``df`` whose ``within`` columns are ordered categoricals in the given order (first appearance
    for a factor without one). With ``strict``, a present level missing from a given order is an error; without,
    it is appended in order of first appearance (a stored study whose configuration was edited afterwards)."""
    out = df.copy()
    for factor in within:
        values = out[factor].astype("string").astype(object).where(out[factor].notna())
        present = [str(v) for v in pd.unique(values.dropna())]
        order = [str(level) for level in (given or {}).get(factor, ())]
        unknown = [level for level in present if level not in order]
        if order and unknown and strict:
            raise AnalysisInputError(
                f"factor {factor!r} has level(s) {unknown} that the given order {order} does not list")
        categories = [level for level in order if level in present] + unknown
        out[factor] = pd.Categorical(values, categories=categories, ordered=True)
    return out


def parse_level_option(values: Sequence[str]) -> dict[str, list[str]]:
    """``["robot=fov_aware,baseline", "kitchen=none_3,mid_2"]`` → ``{"robot": [...], "kitchen": [...]}``."""
    orders: dict[str, list[str]] = {}
    for value in values:
        factor, sep, levels = value.partition("=")
        names = [name.strip() for name in levels.split(",")]
        if not sep or not factor.strip() or not all(names):
            raise AnalysisInputError(f"--levels {value!r}: expected FACTOR=LEVEL,LEVEL,... (e.g. robot=fov_aware,"
                                     "baseline)")
        if factor.strip() in orders:
            raise AnalysisInputError(f"--levels gives factor {factor.strip()!r} twice")
        if len(set(names)) != len(names):
            raise AnalysisInputError(f"--levels {value!r} names a level twice")
        orders[factor.strip()] = names
    return orders
