"""Simulation power of a mixed design: one factor between participants, the rest within (:mod:`analysis.power`
covers designs within participants only).

At each total sample size n the groups get n split as evenly as the study's assignment splits its participants
(the first ``n mod G`` groups one more). Each simulation draws every group's participants with replacement from
that group's own pilot participants (complete cases, as ``analyze`` keeps them), and runs the mixed ANOVA of
``analyze`` (:func:`analysis.mixed_anova.mixed_anova_table`: the between factor, each within effect and its
interaction with the between factor, read by the sphericity rule) on the sample. Power is the share of simulations
with p < α, as for a within design. The mixed analysis's follow-ups (the between factor at each cell, the within
factors in each group) are not simulated. A sample in which a test cannot be computed counts as not significant.

Unlike the within-design tests, these run one simulation at a time: the mixed ANOVA regresses every effect's
contrast scores on the group codes: 1.7 ms a sample with two groups and two conditions (5,000 samples in 8.5 s on
this project's machine), more with more effects.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import pandas as pd

from analysis.cells import complete_cases, factor_levels, group_index, wide_matrix
from analysis.errors import AnalysisInputError
from analysis.mixed_anova import mixed_anova_table
from analysis.power import PILOT, POWER_COLUMNS, wilson


@dataclass(frozen=True, slots=True)
class GroupedData:
    """The pilot's complete cases of one measure in a mixed design."""

    measure: str
    values: np.ndarray
    """Participants × within cells in design order."""
    groups: tuple[int, ...]
    """Each participant's group, an index into ``group_names``."""
    group_names: tuple[str, ...]
    within: tuple[str, ...]
    levels: tuple[tuple[object, ...], ...]
    between: str


def grouped_data(kept: pd.DataFrame, measure: str, within: Sequence[str], between: str, subject: str,
                 group_names: Sequence[str]) -> GroupedData:
    """Complete cases of ``measure`` (as ``analyze`` keeps them) with each participant's group among
    ``group_names`` (the study's levels of ``between``, as text). Raises ``AnalysisInputError`` naming a group
    without a pilot participant who has every cell: its population cannot be resampled."""
    clean, _ = complete_cases(kept, measure, tuple(within), subject, {})
    clean = clean.assign(**{between: clean[between].astype(str)})
    empty = [g for g in group_names if g not in set(clean[between])]
    if empty:
        raise AnalysisInputError(f"{measure}: no pilot participant of {between} = {', '.join(empty)} has a value in "
                                 "every condition of their group; run more pilot participants")
    levels = tuple(tuple(factor_levels(clean, f)) for f in within)
    values, subjects = wide_matrix(clean, measure, within, subject)
    groups = tuple(group_index(clean, subjects, between, subject, group_names))
    return GroupedData(measure, values, groups, tuple(group_names), tuple(within), levels, between)


def group_sizes(n: int, n_groups: int) -> list[int]:
    """``n`` participants split into ``n_groups`` groups as evenly as possible, the first groups one more."""
    return [n // n_groups + (1 if g < n % n_groups else 0) for g in range(n_groups)]


def resample(groups: Sequence[int], sizes: Sequence[int], simulations: int, rng: np.random.Generator
             ) -> tuple[np.ndarray, list[int]]:
    """Row indices (simulations × n) into the pilot's participants, each group's ``sizes[g]`` slots drawn with
    replacement from the participants of group g, and the group of each slot."""
    members = [np.flatnonzero(np.asarray(groups) == g) for g in range(len(sizes))]
    drawn = [pool[rng.integers(len(pool), size=(simulations, size))] for pool, size in zip(members, sizes,
                                                                                            strict=True)]
    slots = [g for g, size in enumerate(sizes) for _ in range(size)]
    return np.concatenate(drawn, axis=1), slots


def mixed_measure_power(data: GroupedData, ns: Sequence[int], simulations: int, alpha: float,
                        rng: np.random.Generator, on_step: Callable[[], None] = lambda: None) -> pd.DataFrame:
    """Rows of :data:`analysis.power.POWER_COLUMNS` for one measure: every row of the mixed ANOVA at every n (the
    total over the groups), with the pilot's effects. ``on_step`` is called after each n."""
    n_groups = len(data.group_names)
    counts = [len(lv) for lv in data.levels]
    if data.values.shape[0] <= n_groups or any(c < 2 for c in counts):
        return pd.DataFrame(columns=POWER_COLUMNS)
    pilot = mixed_anova_table(data.values, data.groups, n_groups, counts, data.within, data.between,
                              intervals=False)
    rows: list[dict[str, object]] = []
    for n in ns:
        sizes = group_sizes(n, n_groups)
        hits = np.zeros(len(pilot), dtype=int)
        if min(sizes) > 0:
            index, slots = resample(data.groups, sizes, simulations, rng)
            for sample in index:
                p = mixed_anova_table(data.values[sample], slots, n_groups, counts, data.within, data.between,
                                      intervals=False)["p_read"].to_numpy(dtype=float)
                hits += np.nan_to_num(p, nan=1.0) < alpha
        for t, row in enumerate(pilot.itertuples(index=False)):
            low, high = wilson(int(hits[t]), simulations)
            rows.append({"measure": data.measure, "test": row.effect, "kind": "effect", "scenario": PILOT, "n": n,
                         "simulations": simulations, "alpha": alpha, "power": int(hits[t]) / simulations,
                         "ci_low": low, "ci_high": high, "pilot_n": data.values.shape[0], "pilot_F": row.F,
                         "pilot_p": row.p_read, "pilot_partial_eta2": row.partial_eta2})
        on_step()
    return pd.DataFrame(rows, columns=POWER_COLUMNS)
