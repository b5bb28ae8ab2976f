"""Simulation power of a mixed design: one factor between participants, the rest within
(:mod:`analysis.power_analysis.within_power` covers designs within participants only).

At each total sample size n the groups get n split as evenly as the study's assignment splits its participants
(the first ``n mod G`` groups one more). Each simulation draws every group's participants with replacement from
that group's own pilot participants (complete cases, as ``analyze`` keeps them), and runs the mixed ANOVA of
``analyze`` (:func:`analysis.statistics.mixed_anova.mixed_anova_table`: the between factor, each within effect and its
interaction with the between factor, read by the sphericity rule) on the sample. Power is the share of simulations
with p < α, as for a within design. The mixed analysis's follow-ups (the between factor at each cell, the within
factors in each group) are not simulated. A sample in which a test cannot be computed counts as not significant.

The mixed ANOVA runs on every simulation at once (:func:`mixed_pvalues`, numpy over a simulations × n × cells
array, as :mod:`analysis.power_analysis.within_power` does for a within design): the groups' sizes are fixed at each n,
so every sample has the same design and each effect's regression on the group codes is one set of matrix products. It
computes what :func:`analysis.statistics.mixed_anova.mixed_anova_table` computes for ``p_read`` (F, ε_GG and ε_HF from
the pooled within-group covariance, the reading rule, the untestable cases);
``tests/analysis/power_analysis/test_mixed_power.py`` checks it against that function sample by sample.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import pandas as pd
from scipy import stats

from analysis.power_analysis.within_power import PILOT, POWER_COLUMNS, wilson
from analysis.preparation.cells import complete_cases, factor_levels, group_index, wide_matrix
from analysis.source.input_errors import AnalysisInputError
from analysis.statistics.anova import GG_THRESHOLD, effects_of
from analysis.statistics.mixed_anova import check_ss_type, group_codes, mixed_anova_table
from analysis.statistics.sphericity import effect_contrasts

BLOCK_VALUES = 4_000_000
"""Samples are simulated in blocks of at most this many values (samples × n × cells), to bound the memory."""


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


def mixed_pvalues(stack: np.ndarray, slots: Sequence[int], n_groups: int, levels: Sequence[int],
                  within: Sequence[str], ss_type: int = 3) -> tuple[np.ndarray, np.ndarray]:
    """``(F, p)``, each samples × effects in :func:`~analysis.statistics.mixed_anova.mixed_anova_table`'s row order, of
    every sample of ``stack`` (samples × N participants × cells in design order) whose participant j is in group
    ``slots[j]``; p is the one ``analyze`` reads (the sphericity rule), NaN where the test cannot be computed."""
    check_ss_type(ss_type)
    sims, n, _ = stack.shape
    dof = n - n_groups
    x = group_codes(slots, n_groups)
    xtx_inv = np.linalg.pinv(x.T @ x)
    fit = xtx_inv @ x.T
    codes = np.eye(n_groups)[1:]
    middle = np.linalg.pinv(codes @ xtx_inv @ codes.T)
    total = ((stack - stack.mean(axis=(1, 2), keepdims=True)) ** 2).sum(axis=(1, 2))
    tiny = 1e-12 * np.maximum(total, 1.0)
    f_rows, p_rows = [], []

    def test(ss: np.ndarray, error: np.ndarray, df1: int, d: int, eps: np.ndarray) -> None:
        df2 = d * dof
        with np.errstate(divide="ignore", invalid="ignore"):
            f = (ss / df1) / (error / df2) if df2 > 0 else np.full(sims, np.nan)
            testable = (df2 > 0) & (total > tiny) & (error > tiny)
            f = np.where(testable, f, np.nan)
            p = stats.f.sf(f, df1 * eps, df2 * eps)
        f_rows.append(f)
        p_rows.append(np.where(testable, p, np.nan))

    def group_ss(z: np.ndarray) -> np.ndarray:
        kb = np.einsum("qn,snd->sqd", codes @ fit, z)
        return np.asarray(np.einsum("sqd,qp,spd->s", kb, middle, kb))

    def residual_sscp(z: np.ndarray) -> np.ndarray:
        residual = z - np.einsum("ng,gm,smd->snd", x, fit, z)
        return np.asarray(np.einsum("snd,sne->sde", residual, residual))

    z = stack @ effect_contrasts(levels, ())
    test(group_ss(z), residual_sscp(z)[:, 0, 0], n_groups - 1, 1, np.ones(sims))
    for effect in effects_of(within):
        z = stack @ effect_contrasts(levels, effect)
        d = z.shape[2]
        sscp = residual_sscp(z)
        error = np.trace(sscp, axis1=1, axis2=2)
        if ss_type == 2:
            ss_within = n * (z.mean(axis=1) ** 2).sum(axis=1)
        else:
            beta = np.einsum("gn,snd->sgd", fit, z)
            ss_within = np.einsum("sd,sd->s", beta[:, 0], beta[:, 0]) / xtx_inv[0, 0]
        eps = _read_epsilon(sscp / max(dof, 1), d, dof)
        test(ss_within, error, d, d, eps)
        test(group_ss(z), error, (n_groups - 1) * d, d, eps)
    return np.stack(f_rows, axis=1), np.stack(p_rows, axis=1)


def _read_epsilon(m: np.ndarray, d: int, dof: int) -> np.ndarray:
    """The ε the reading rule applies (1, ε_GG or min(ε_HF, 1)) for each sample's pooled error covariance ``m``
    (samples × d × d on ``dof`` df), as :func:`analysis.statistics.sphericity.covariance_sphericity` and
    :func:`analysis.statistics.anova.reading` choose it."""
    if d == 1:
        return np.ones(m.shape[0])
    with np.errstate(divide="ignore", invalid="ignore"):
        trace = np.trace(m, axis1=1, axis2=2)
        gg = trace ** 2 / (d * np.einsum("sde,sed->s", m, m))
        room = dof - d * gg
        hf = np.where(room > 0, ((dof + 1) * d * gg - 2) / (d * room), np.nan)
    gg = np.where(trace > 0, gg, np.nan)
    use_hf = (gg > GG_THRESHOLD) & np.isfinite(hf)
    return np.where(np.isfinite(gg), np.where(use_hf, np.minimum(hf, 1.0), gg), 1.0)


def mixed_measure_power(data: GroupedData, ns: Sequence[int], simulations: int, alpha: float,
                        rng: np.random.Generator, on_step: Callable[[], None] = lambda: None,
                        ss_type: int = 3) -> pd.DataFrame:
    """Rows of :data:`analysis.power_analysis.within_power.POWER_COLUMNS` for one measure: every row of the mixed ANOVA
    at every n (the total over the groups), with the pilot's effects. ``on_step`` is called after each n."""
    n_groups = len(data.group_names)
    counts = [len(lv) for lv in data.levels]
    if data.values.shape[0] <= n_groups or any(c < 2 for c in counts):
        return pd.DataFrame(columns=POWER_COLUMNS)
    pilot = mixed_anova_table(data.values, data.groups, n_groups, counts, data.within, data.between,
                              intervals=False, ss_type=ss_type)
    rows: list[dict[str, object]] = []
    for n in ns:
        sizes = group_sizes(n, n_groups)
        hits = np.zeros(len(pilot), dtype=int)
        if min(sizes) > 0:
            index, slots = resample(data.groups, sizes, simulations, rng)
            block = max(1, BLOCK_VALUES // (n * data.values.shape[1]))
            for start in range(0, simulations, block):
                _, p = mixed_pvalues(data.values[index[start:start + block]], slots, n_groups, counts, data.within,
                                     ss_type)
                hits += (np.nan_to_num(p, nan=1.0) < alpha).sum(axis=0)
        for t, row in enumerate(pilot.itertuples(index=False)):
            low, high = wilson(int(hits[t]), simulations)
            rows.append({"measure": data.measure, "test": row.effect, "kind": "effect", "scenario": PILOT, "n": n,
                         "simulations": simulations, "alpha": alpha, "power": int(hits[t]) / simulations,
                         "ci_low": low, "ci_high": high, "pilot_n": data.values.shape[0], "pilot_F": row.F,
                         "pilot_p": row.p_read, "pilot_partial_eta2": row.partial_eta2})
        on_step()
    return pd.DataFrame(rows, columns=POWER_COLUMNS)
