"""Simulation power analysis from pilot data: resample participants with replacement, rerun the planned tests.

For each measure, each planned test (every main effect and interaction of the within factors, read as
``analyze`` reads it, and the simple effect of each factor at every level of the others, Holm-adjusted within
its family as ``analyze`` adjusts it; :mod:`analysis.statistics.anova`, :mod:`analysis.followups.simple_effects`) and
each sample size n: draw ``simulations`` samples of n participants with replacement from the pilot's complete cases, run
the test on each, and count how often p < α. Power is that share, with a Wilson 95 % interval for the Monte-Carlo error.

The computation is the analysis's. An effect with one degree of freedom (every effect of a design whose factors
have two levels) is the contrast form of :func:`analysis.statistics.anova.anova_table`: with the participants' contrast
scores z (``effect_contrasts``), F = n z̄² / (Σ (z − z̄)² / (n − 1)) on (1, n − 1) df, and no sphericity correction
applies. Any other effect computes what :func:`analysis.statistics.anova.anova_table` computes for ``p_read`` (F, ε_GG,
ε_HF, the reading rule) from the contrast scores' covariance (:func:`read_p`). Both run on every simulation at
once (numpy over a simulations × n × cells array), as does the Holm adjustment;
``tests/analysis/power_analysis/test_within_power.py`` checks them against ``anova_table`` and ``simple_effects``. A
resample in which a test cannot be computed (no error variance) counts as not significant.

Resampled participants are distinct subjects (a participant drawn twice counts twice), as in a bootstrap of
the pilot's population.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import pandas as pd
from scipy import stats

from analysis.power_analysis.chosen_effect import EffectSize, with_effect_size
from analysis.preparation.cells import complete_cases, factor_levels, wide_matrix
from analysis.statistics.anova import GG_THRESHOLD, effect_name, effects_of
from analysis.statistics.sphericity import effect_contrasts

PILOT = "pilot"
"""The scenario of the pilot's own effects (the other: a chosen effect size,
:mod:`analysis.power_analysis.chosen_effect`)."""
POWER_COLUMNS = ["measure", "test", "kind", "scenario", "n", "simulations", "alpha", "power", "ci_low", "ci_high",
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
    effect: tuple[int, ...] = ()
    """An omnibus effect's factor positions."""


def planned_tests(within: Sequence[str], levels: Sequence[Sequence[object]]) -> list[PlannedTest]:
    """Every omnibus effect, then every simple effect (each factor at each combination of the others' levels)."""
    counts = [len(lv) for lv in levels]
    tests = [PlannedTest(effect_name(within, e), "effect", effect_contrasts(counts, e), effect=e)
             for e in effects_of(within)]
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


def read_p(z: np.ndarray, total: np.ndarray) -> np.ndarray:
    """The p ``analyze`` reads for an effect with d > 1 df, on every sample at once: ``z`` is simulations × n × d
    (the effect's contrast scores), ``total`` each sample's total sum of squares over the cells tested. The
    statistics of :func:`analysis.statistics.anova.anova_table` and :func:`analysis.statistics.sphericity.sphericity`
    (ε_GG, ε_HF, the reading rule, the untestable cases) written for a stack of samples."""
    _, n, d = z.shape
    mean = z.mean(axis=1)
    centred = z - mean[:, None, :]
    ss = n * (mean ** 2).sum(axis=-1)
    ss_err = (centred ** 2).sum(axis=(1, 2))
    cov = np.einsum("snd,sne->sde", centred, centred) / max(n - 1, 1)
    with np.errstate(divide="ignore", invalid="ignore"):
        gg = np.trace(cov, axis1=1, axis2=2) ** 2 / (d * np.einsum("sde,sed->s", cov, cov))
        room = n - 1 - d * gg
        hf = np.where(room > 0, (n * d * gg - 2) / (d * room), np.nan)
        eps = np.where((gg > GG_THRESHOLD) & np.isfinite(hf), np.minimum(hf, 1.0), gg)
        f = (ss / d) / (ss_err / (d * (n - 1)))
        p = stats.f.sf(f, d * eps, d * (n - 1) * eps)
    tiny = 1e-12 * np.maximum(total, 1.0)
    testable = (n >= 2) & (total > tiny) & (ss_err > tiny)
    return np.where(testable, p, np.nan)


def holm_matrix(p: np.ndarray) -> np.ndarray:
    """Holm-adjusted p along the last axis (NaN left out of m and kept NaN), every row at once."""
    missing = np.isnan(p)
    filled = np.where(missing, np.inf, p)
    order = np.argsort(filled, axis=-1, kind="stable")
    ranked = np.take_along_axis(filled, order, axis=-1)
    m = (~missing).sum(axis=-1, keepdims=True)
    with np.errstate(invalid="ignore"):
        adjusted = np.maximum.accumulate(np.minimum(1.0, (m - np.arange(p.shape[-1])) * ranked), axis=-1)
    out = np.empty_like(adjusted)
    np.put_along_axis(out, order, adjusted, axis=-1)
    return np.where(missing, np.nan, out)


def sample_pvalues(values: np.ndarray, tests: Sequence[PlannedTest]) -> np.ndarray:
    """p (as ``analyze`` reads it) of every test on every sample: ``values`` is simulations × n × cells;
    the answer simulations × tests."""
    sims = values.shape[0]
    p = np.full((sims, len(tests)), np.nan)
    for t, test in enumerate(tests):
        z = values @ test.contrast
        if test.contrast.shape[1] == 1:
            p[:, t] = one_df_p(z[..., 0])
        else:
            cells = values[..., np.abs(test.contrast).sum(axis=1) > 0]
            total = ((cells - cells.mean(axis=(1, 2), keepdims=True)) ** 2).sum(axis=(1, 2))
            p[:, t] = read_p(z, total)
    for family in {t.family for t in tests if t.kind == "simple"}:
        cols = [i for i, t in enumerate(tests) if t.kind == "simple" and t.family == family]
        p[:, cols] = holm_matrix(p[:, cols])
    return p


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
                  rng: np.random.Generator, effect_size: EffectSize | None = None,
                  on_step: Callable[[], None] = lambda: None) -> pd.DataFrame:
    """Rows of :data:`POWER_COLUMNS` for one measure: every planned test at every n with the pilot's effects
    (scenario ``pilot``), then, with ``effect_size``, every omnibus effect set to that size. ``on_step`` is called
    after each n of each scenario."""
    counts = [len(lv) for lv in data.levels]
    tests = planned_tests(data.within, data.levels)
    pilot_n = data.values.shape[0]
    if pilot_n < 2 or any(c < 2 for c in counts):
        return pd.DataFrame(columns=POWER_COLUMNS)
    rows = _scenario_rows(data, data.values, tests, PILOT, ns, simulations, alpha, rng, on_step)
    if effect_size is not None:
        for test in (t for t in tests if t.kind == "effect"):
            scaled = with_effect_size(data.values, counts, data.within, test.effect, test.contrast,
                                      effect_size.eta2g)
            if scaled is not None:
                rows += _scenario_rows(data, scaled, [test], effect_size.label, ns, simulations, alpha, rng,
                                       on_step)
    return pd.DataFrame(rows, columns=POWER_COLUMNS)


def _scenario_rows(data: MeasureData, values: np.ndarray, tests: Sequence[PlannedTest], scenario: str,
                   ns: Sequence[int], simulations: int, alpha: float, rng: np.random.Generator,
                   on_step: Callable[[], None]) -> list[dict[str, object]]:
    pilot_n = values.shape[0]
    pilot_p = sample_pvalues(values[None], tests)[0]
    pilot_stats = [_pilot_stats(values, t) for t in tests]
    rows: list[dict[str, object]] = []
    for n in ns:
        idx = rng.integers(pilot_n, size=(simulations, n))
        p = sample_pvalues(values[idx], tests)
        for t, test in enumerate(tests):
            hits = int(np.sum(np.nan_to_num(p[:, t], nan=1.0) < alpha))
            low, high = wilson(hits, simulations)
            f, eta = pilot_stats[t]
            rows.append({"measure": data.measure, "test": test.name, "kind": test.kind, "scenario": scenario,
                         "n": n, "simulations": simulations, "alpha": alpha, "power": hits / simulations,
                         "ci_low": low, "ci_high": high, "pilot_n": pilot_n, "pilot_F": f, "pilot_p": pilot_p[t],
                         "pilot_partial_eta2": eta})
        on_step()
    return rows


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
    """Per measure, scenario and test: the smallest n of the grid whose power reaches ``target`` (empty when none
    does)."""
    rows = []
    for (measure, scenario, test), part in table.groupby(["measure", "scenario", "test"], sort=False):
        reached = part[part["power"] >= target]
        rows.append({"measure": measure, "scenario": scenario, "test": test,
                     f"n_{int(target * 100)}": int(reached["n"].min()) if len(reached) else None})
    return pd.DataFrame(rows)
