"""Simulation power analysis from pilot data: resample participants with replacement, rerun the planned tests.

For each measure, each planned test (every main effect and interaction of the within factors, read as
``analyze`` reads it, and the simple effect of each factor at every level of the others, Holm-adjusted within
its family as ``analyze`` adjusts it; :mod:`analysis.anova`, :mod:`analysis.followups`) and each sample size n:
draw ``simulations`` samples of n participants with replacement from the pilot's complete cases, run the test
on each, and count how often p < α. Power is that share, with a Wilson 95 % interval for the Monte-Carlo error.

The computation is the analysis's. An effect with one degree of freedom (every effect of a design whose factors
have two levels) is the contrast form of :func:`analysis.anova.anova_table`: with the participants' contrast
scores z (``effect_contrasts``), F = n z̄² / (Σ (z − z̄)² / (n − 1)) on (1, n − 1) df, and no sphericity correction
applies; this path runs on every simulation at once (vectorised). Any other effect runs
:func:`analysis.anova.anova_table` itself on each sample and reads ``p_read``. ``tests/analysis/test_power.py``
checks both paths against ``anova_table`` and ``simple_effects``. A resample in which a test cannot be computed (no
error variance) counts as not significant.

Resampled participants are distinct subjects (a participant drawn twice counts twice), as in a bootstrap of
the pilot's population.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import pandas as pd
from scipy import stats

from analysis.anova import anova_table, effect_name, effects_of
from analysis.cells import complete_cases, factor_levels, wide_matrix
from analysis.sphericity import effect_contrasts

POWER_COLUMNS = ["measure", "test", "kind", "n", "simulations", "alpha", "power", "ci_low", "ci_high",
                 "pilot_n", "pilot_F", "pilot_p", "pilot_partial_eta2"]


@dataclass(frozen=True, slots=True)
class PlannedTest:
    """One test: an omnibus effect (``kind`` ``effect``) or a simple effect (``simple``) of ``factor`` at
    ``at`` (levels of the other factors), in a Holm family of ``family`` simple effects."""

    name: str
    kind: str
    contrast: np.ndarray
    """Columns: the effect's contrasts over the design's cells (cells outside a simple effect's slice are 0)."""
    family: str = ""


def planned_tests(within: Sequence[str], levels: Sequence[Sequence[object]]) -> list[PlannedTest]:
    """Every omnibus effect, then every simple effect (each factor at each combination of the others' levels)."""
    counts = [len(lv) for lv in levels]
    tests = [PlannedTest(effect_name(within, e), "effect", effect_contrasts(counts, e)) for e in effects_of(within)]
    if len(within) < 2:
        return tests
    cells = list(itertools.product(*levels))
    for f, factor in enumerate(within):
        others = [i for i in range(len(within)) if i != f]
        for combo in itertools.product(*(levels[i] for i in others)):
            at = ", ".join(f"{within[i]}={lv}" for i, lv in zip(others, combo, strict=True))
            slice_cells = [c for c, cell in enumerate(cells) if all(cell[i] == lv for i, lv in zip(others, combo,
                                                                                                  strict=True))]
            inner = effect_contrasts([counts[f]], (0,))
            contrast = np.zeros((len(cells), inner.shape[1]))
            contrast[slice_cells, :] = inner
            tests.append(PlannedTest(f"{factor} at {at}", "simple", contrast, family=factor))
    return tests


def one_df_p(z: np.ndarray) -> np.ndarray:
    """p of F = n z̄² / (Σ(z − z̄)²/(n − 1)) on (1, n − 1) df for each row of ``z`` (simulations × n); NaN when
    there is no error variance."""
    n = z.shape[-1]
    mean = z.mean(axis=-1)
    ss_error = ((z - mean[..., None]) ** 2).sum(axis=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        f = n * mean ** 2 / (ss_error / (n - 1))
    f = np.where(ss_error > 1e-12 * np.maximum(1.0, n * mean ** 2), f, np.nan)
    return np.asarray(stats.f.sf(f, 1, n - 1))


def holm_matrix(p: np.ndarray) -> np.ndarray:
    """Holm-adjusted p along the last axis (NaN left out of m and kept NaN), row by row."""
    out = np.full_like(p, np.nan)
    for row in range(p.shape[0]):
        ok = ~np.isnan(p[row])
        values = p[row, ok]
        m = len(values)
        order = np.argsort(values)
        adjusted = np.empty(m)
        running = 0.0
        for rank, i in enumerate(order):
            running = max(running, min(1.0, (m - rank) * values[i]))
            adjusted[i] = running
        out[row, ok] = adjusted
    return out


def sample_pvalues(values: np.ndarray, levels: Sequence[int], within: Sequence[str],
                 tests: Sequence[PlannedTest]) -> np.ndarray:
    """p (as ``analyze`` reads it) of every test on every sample: ``values`` is simulations × n × cells;
    the answer simulations × tests."""
    sims = values.shape[0]
    p = np.full((sims, len(tests)), np.nan)
    for t, test in enumerate(tests):
        if test.contrast.shape[1] == 1:
            p[:, t] = one_df_p(values @ test.contrast[:, 0])
        else:
            p[:, t] = [_slow_p(sample, levels, within, test) for sample in values]
    for family in {t.family for t in tests if t.kind == "simple"}:
        cols = [i for i, t in enumerate(tests) if t.kind == "simple" and t.family == family]
        p[:, cols] = holm_matrix(p[:, cols])
    return p


def _slow_p(sample: np.ndarray, levels: Sequence[int], within: Sequence[str], test: PlannedTest) -> float:
    """``anova_table``'s ``p_read`` for an effect with more than one df (sphericity corrections included)."""
    if test.kind == "effect":
        table = anova_table(sample, levels, within)
        return float(table.loc[table["effect"] == test.name, "p_read"].iloc[0])
    cols = np.flatnonzero(np.abs(test.contrast).sum(axis=1) > 0)
    factor_levels_count = test.contrast.shape[1] + 1
    table = anova_table(sample[:, cols], [factor_levels_count], [test.family])
    return float(table["p_read"].iloc[0])


def wilson(successes: int, trials: int, z: float = 1.959963984540054) -> tuple[float, float]:
    """Wilson score interval of a proportion (the Monte-Carlo error of a power estimate)."""
    if trials == 0:
        return (math.nan, math.nan)
    phat = successes / trials
    centre = (phat + z * z / (2 * trials)) / (1 + z * z / trials)
    half = z * math.sqrt(phat * (1 - phat) / trials + z * z / (4 * trials * trials)) / (1 + z * z / trials)
    return (max(0.0, centre - half), min(1.0, centre + half))


@dataclass(frozen=True, slots=True)
class MeasureData:
    """The pilot's complete cases of one measure as the analysis sees them."""

    measure: str
    values: np.ndarray
    """Participants × cells in design order."""
    within: tuple[str, ...]
    levels: tuple[tuple[object, ...], ...]


def measure_data(kept: pd.DataFrame, measure: str, within: Sequence[str], subject: str) -> MeasureData:
    """Complete cases of ``measure`` in the analysis's table (exclusions already applied), as ``analyze``."""
    clean, _ = complete_cases(kept, measure, tuple(within), subject, {})
    levels = tuple(tuple(factor_levels(clean, f)) for f in within)
    values, _ = wide_matrix(clean, measure, within, subject) if len(clean) else (np.empty((0, 0)), [])
    return MeasureData(measure, values, tuple(within), levels)


def measure_power(data: MeasureData, ns: Sequence[int], simulations: int, alpha: float,
                  rng: np.random.Generator) -> pd.DataFrame:
    """Rows of :data:`POWER_COLUMNS` for one measure: every planned test at every n."""
    counts = [len(lv) for lv in data.levels]
    tests = planned_tests(data.within, data.levels)
    pilot_n = data.values.shape[0]
    rows = []
    if pilot_n < 2 or any(c < 2 for c in counts):
        return pd.DataFrame(columns=POWER_COLUMNS)
    pilot_p = sample_pvalues(data.values[None], counts, data.within, tests)[0]
    pilot_stats = [_pilot_stats(data.values, t) for t in tests]
    for n in ns:
        idx = rng.integers(pilot_n, size=(simulations, n))
        p = sample_pvalues(data.values[idx], counts, data.within, tests)
        for t, test in enumerate(tests):
            hits = int(np.sum(np.nan_to_num(p[:, t], nan=1.0) < alpha))
            low, high = wilson(hits, simulations)
            f, eta = pilot_stats[t]
            rows.append({"measure": data.measure, "test": test.name, "kind": test.kind, "n": n,
                         "simulations": simulations, "alpha": alpha, "power": hits / simulations, "ci_low": low,
                         "ci_high": high, "pilot_n": pilot_n, "pilot_F": f, "pilot_p": pilot_p[t],
                         "pilot_partial_eta2": eta})
    return pd.DataFrame(rows, columns=POWER_COLUMNS)


def _pilot_stats(values: np.ndarray, test: PlannedTest) -> tuple[float, float]:
    """The pilot's F and partial η² of a test (contrast form; NaN without error variance)."""
    z = values @ test.contrast
    n, d = z.shape
    mean = z.mean(axis=0)
    ss = n * float(mean @ mean)
    err = float(((z - mean) ** 2).sum())
    if err <= 0:
        return (math.nan, math.nan)
    return ((ss / d) / (err / (d * (n - 1))), ss / (ss + err))


def n_reaching(table: pd.DataFrame, target: float) -> pd.DataFrame:
    """Per measure and test: the smallest n of the grid whose power reaches ``target`` (empty when none does)."""
    rows = []
    for (measure, test), part in table.groupby(["measure", "test"], sort=False):
        reached = part[part["power"] >= target]
        rows.append({"measure": measure, "test": test,
                     f"n_{int(target * 100)}": int(reached["n"].min()) if len(reached) else None})
    return pd.DataFrame(rows)
