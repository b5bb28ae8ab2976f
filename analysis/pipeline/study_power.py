"""``power_study``: the simulation power analysis of a stored study's pilot participants
(:mod:`analysis.power_analysis.within_power`; :mod:`analysis.power_analysis.mixed_power` for a study with a factor
between participants).

Steps: export the study with its pilot participants (``<out>/data/``, as ``analyze --include-pilot`` does);
keep the cells of pilot participants only (the people whose behaviour the pilot simulated); prepare the
table exactly as ``analyze`` does (the study's level order, scale scores, exclusion rules; then each measure's
complete cases); then, per measure, resample at each n. Measures run in parallel over ``jobs`` processes, each
with its own generator from ``[seed, measure index]`` (same seed, same result, whatever ``jobs``).

Files written to ``out``:

    power.csv      one row per measure × test × n (``analysis.power_analysis.within_power.POWER_COLUMNS``; ``power`` the
                   share of simulations with p < α, ``ci_low`` / ``ci_high`` its Wilson 95 % Monte-Carlo interval)
    n_needed.csv   per measure and test, the smallest n of the grid reaching 80 % and 90 % power (empty: none)
    power.png      power against n, one panel per measure, one line per test
    power.md       a short report
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd
from sqlalchemy import Engine

from analysis.exports.study_export import export_study
from analysis.measures.scale_scores import score_scales
from analysis.pipeline.analyze_study import (
    DATA_DIR,
    DEFAULT_MEASURES,
    SUBJECT,
    attach_trial_columns,
    read_cells,
    varied_factors,
)
from analysis.power_analysis.chosen_effect import EffectSize
from analysis.power_analysis.mixed_power import GroupedData, grouped_data, mixed_measure_power
from analysis.power_analysis.within_power import (
    PILOT,
    POWER_COLUMNS,
    MeasureData,
    measure_data,
    measure_power,
    n_reaching,
)
from analysis.preparation.exclusions import apply_exclusions
from analysis.preparation.levels import apply_level_order
from analysis.source.input_errors import AnalysisInputError
from analysis.source.study_design import StudyDesign

TARGETS = (0.8, 0.9)
SMALL_PILOT = 10
"""Below this many pilot participants the report warns that the resampled population is too small."""
MIN_PILOTS = 2
"""A measure is simulated from at least this many complete pilot participants (in each group of a mixed design):
one participant resampled is one person repeated, with no spread to resample."""


@dataclass(frozen=True, slots=True, eq=False)
class PowerResult:
    table: pd.DataFrame
    needed: pd.DataFrame
    pilot_participants: int
    files: tuple[Path, ...]
    not_simulated: dict[str, str]
    """Measures with too few complete pilot participants, and why (the others were simulated)."""


def too_few(data: MeasureData | GroupedData) -> str:
    """Why ``data`` has too few complete pilot participants to simulate (empty when it has enough)."""
    if isinstance(data, GroupedData):
        counts = np.bincount(np.asarray(data.groups, dtype=int), minlength=len(data.group_names))
        short = [f"{name} {count}" for name, count in zip(data.group_names, counts, strict=True)
                 if count < MIN_PILOTS]
        return (f"{', '.join(short)} complete pilot participant(s) in the group(s) of {data.between}; each group "
                f"needs {MIN_PILOTS}") if short else ""
    n = data.values.shape[0]
    return f"{n} complete pilot participant(s); at least {MIN_PILOTS} are needed" if n < MIN_PILOTS else ""


@dataclass(frozen=True, slots=True, eq=False)
class PilotTable:
    """The analysis table of the pilot participants (exclusions applied) and how to read it."""

    kept: pd.DataFrame
    within: list[str]
    between: str | None
    """The factor between participants (a mixed design), if any."""
    design: StudyDesign
    pilots: int
    """Pilot participants in the study (with or without complete cells)."""


def pilot_table(source: Engine | str, study_id: str, out: Path, include: frozenset[str] = frozenset()) -> PilotTable:
    """The pilot participants' table as ``analyze`` prepares it (see the module docstring)."""
    export = export_study(source, study_id, out / DATA_DIR, include_pilot=True)
    cells = read_cells(out)
    people = export.dataset.tables["participants.csv"]
    pilots = set(people.loc[people["pilot"].astype(int) == 1, "participant"].astype(str))
    trials = pd.read_csv(out / DATA_DIR / "trials.csv", dtype={SUBJECT: str})
    cells = attach_trial_columns(cells[cells[SUBJECT].isin(pilots)], trials)
    if cells.empty:
        raise AnalysisInputError(f"study {study_id!r} has no pilot participant with a finished main trial; run "
                                 f"steakhouse pilot first")
    design = StudyDesign.from_config(export.dataset.config)
    within, between = varied_factors(cells, design)
    if len(between) > 1:
        raise AnalysisInputError(f"study {study_id!r} has {len(between)} factors between participants in the "
                                 f"pilot ({', '.join(between)}); the power simulation takes one")
    if not within:
        raise AnalysisInputError(f"study {study_id!r}: no within factor with two levels in the pilot's cells")
    table = apply_level_order(cells, [*within, *between], design.levels, strict=False)
    table = score_scales(table, design.items, design.scales) if design.scales else table
    kept, _ = apply_exclusions(table, within, SUBJECT, include)
    return PilotTable(kept, within, between[0] if between else None, design, len(pilots))


Task = tuple[MeasureData | GroupedData, tuple[int, ...], int, float, int, int, EffectSize | None, int]


def _one(args: Task, on_step: Callable[[], None] = lambda: None) -> pd.DataFrame:
    data, ns, simulations, alpha, seed, index, effect_size, ss_type = args
    rng = np.random.default_rng([seed, index])
    if isinstance(data, GroupedData):
        return mixed_measure_power(data, ns, simulations, alpha, rng, on_step, ss_type)
    return measure_power(data, ns, simulations, alpha, rng, effect_size, on_step)


def steps_per_measure(within: Sequence[str], ns: Sequence[int], effect_size: EffectSize | None) -> int:
    """Progress steps of one measure: one per n, for the pilot's effects and for each omnibus effect at the chosen
    size (within designs only)."""
    return len(ns) * (1 + (2 ** len(within) - 1 if effect_size is not None else 0))


def power_study(source: Engine | str, study_id: str, out_dir: Path | str, ns: Sequence[int], *,
                simulations: int = 1000, alpha: float = 0.05, jobs: int = 1, seed: int = 0,
                measures: Sequence[str] | None = None, include: frozenset[str] = frozenset(),
                on_measure: Callable[[str], None] = lambda name: None, plots: bool = True,
                on_start: Callable[[int], None] = lambda steps: None, on_step: Callable[[int], None] = lambda k: None,
                effect_size: EffectSize | None = None, ss_type: int = 3) -> PowerResult:
    """Power of every planned test of ``measures`` at each of ``ns`` (see the module docstring); ``on_start``
    gets the number of progress steps, ``on_step`` is called with each step count done, ``on_measure`` with each
    measure done. ``ss_type``: the sums of squares of a mixed design's ANOVA
    (:mod:`analysis.statistics.mixed_anova`)."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    pilot = pilot_table(source, study_id, out, include)
    kept, within, design, n_pilots = pilot.kept, pilot.within, pilot.design, pilot.pilots
    if pilot.between is not None and effect_size is not None:
        raise AnalysisInputError(f"study {study_id!r} has {pilot.between} between participants: a chosen effect "
                                 "size (--effect) is simulated for designs within participants only")
    chosen = list(measures) if measures is not None else [*DEFAULT_MEASURES, *(s.column for s in design.scales)]
    missing = [m for m in chosen if m not in kept.columns]
    if missing:
        raise AnalysisInputError(f"no column {', '.join(missing)} in the pilot's cells")
    between = pilot.between
    datas: list[MeasureData | GroupedData] = (
        [measure_data(kept, m, within, SUBJECT) for m in chosen] if between is None else
        [grouped_data(kept, m, within, between, SUBJECT, _groups(kept, between, design)) for m in chosen])
    short = {d.measure: reason for d in datas if (reason := too_few(d))}
    if len(short) == len(datas):
        raise AnalysisInputError("too few pilot participants to simulate: " + "; ".join(
            f"{m}: {reason}" for m, reason in short.items()) + f". Run more (steakhouse pilot --participants "
            f"{SMALL_PILOT * 2} or more)")
    # i stays the measure's position among those chosen: its generator, whichever others are left out
    simulated = [(i, d) for i, d in enumerate(datas) if d.measure not in short]
    datas = [d for _, d in simulated]
    per_measure = steps_per_measure(within, ns, effect_size)
    on_start(len(datas) * per_measure)
    tasks: list[Task] = [(d, tuple(ns), simulations, alpha, seed, i, effect_size, ss_type)
                         for i, d in simulated]
    frames: list[pd.DataFrame] = []
    if jobs > 1 and len(tasks) > 1:
        with ProcessPoolExecutor(max_workers=jobs) as pool:
            for data, frame in zip(datas, pool.map(_one, tasks), strict=True):
                frames.append(frame)
                on_step(per_measure)
                on_measure(data.measure)
    else:
        for task in tasks:
            frames.append(_one(task, lambda: on_step(1)))
            on_measure(task[0].measure)
    table = pd.concat([f for f in frames if not f.empty] or [pd.DataFrame(columns=POWER_COLUMNS)],
                      ignore_index=True)
    needed = _needed(table)
    files = [out / "power.csv", out / "n_needed.csv"]
    table.to_csv(files[0], index=False)
    needed.to_csv(files[1], index=False)
    if plots and not table.empty:
        files.append(_plot(table, out / "power.png", alpha))
    files.append(_report(table, needed, out / "power.md", study_id, n_pilots, simulations, alpha, between,
                         short, plotted=files[-1].name == "power.png"))
    return PowerResult(table, needed, n_pilots, tuple(files), short)


def _groups(kept: pd.DataFrame, between: str, design: StudyDesign) -> list[str]:
    """The groups of ``between``: the study's levels, then any other level the pilot's cells hold (a study whose
    configuration was edited afterwards), as ``apply_level_order`` names them."""
    study = [str(level) for level in design.levels.get(between, ())]
    return study + [str(level) for level in kept[between].cat.categories if str(level) not in study]


def _needed(table: pd.DataFrame) -> pd.DataFrame:
    if table.empty:
        return pd.DataFrame(columns=["measure", "scenario", "test", "n_80", "n_90"])
    a, b = (n_reaching(table, t) for t in TARGETS)
    return a.merge(b, on=["measure", "scenario", "test"])


def _plot(table: pd.DataFrame, path: Path, alpha: float) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    measures = list(dict.fromkeys(table["measure"]))
    cols = min(3, len(measures))
    rows = -(-len(measures) // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(5 * cols, 3.6 * rows), squeeze=False)
    for ax, measure in zip(axes.flat, measures, strict=False):
        part = table[table["measure"] == measure]
        for (scenario, test), line in part.groupby(["scenario", "test"], sort=False):
            label = test if scenario == PILOT else f"{test} ({scenario})"
            ax.plot(line["n"], line["power"], marker="o", label=label, linestyle="-" if scenario == PILOT else ":")
            ax.fill_between(line["n"], line["ci_low"], line["ci_high"], alpha=0.15)
        for target in TARGETS:
            ax.axhline(target, color="grey", linewidth=0.7, linestyle="--")
        ax.set_title(measure)
        ax.set_xlabel("participants (n)")
        ax.set_ylabel(f"power (α = {alpha:g})")
        ax.set_ylim(0, 1)
        ax.legend(fontsize=6)
    for ax in list(axes.flat)[len(measures):]:
        ax.set_visible(False)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def _report(table: pd.DataFrame, needed: pd.DataFrame, path: Path, study_id: str, n_pilots: int,
            simulations: int, alpha: float, between: str | None, short: dict[str, str], plotted: bool) -> Path:
    lines = [f"# Power analysis: study {study_id}", "",
             f"Simulated from {n_pilots} pilot participants (steakhouse pilot: simulated participants, not people): "
             f"{simulations} resamples with replacement at each n, α = {alpha:g}, the tests `analyze` runs "
             "(simple effects Holm-adjusted). Power is the share of resamples with p < α; the interval is its "
             "Wilson 95 % Monte-Carlo interval. A pilot of simulated participants estimates power for people who "
             "behave like the simulation; treat the numbers as a rehearsal.", "",
             "Rows whose effect size is `eta2g=…` set that omnibus effect's generalized η² to the chosen value "
             "(`--effect`), keeping the pilot's pattern of means and its error terms; their F and partial η² are "
             "those of the pilot so changed.", "",
             *([f"A mixed design: {between} is between participants. n is the total, split between the groups of "
                f"{between} as evenly as assignment splits them, each group resampled from its own pilot "
                "participants; the tests are the mixed ANOVA's (the between factor, each within effect and its "
                "interaction with it). Its follow-ups are not simulated.", ""] if between else []),
             "| measure | effect size | test | pilot F | pilot partial η² | n for 80 % | n for 90 % |",
             "|---|---|---|---|---|---|---|"]
    first = table.drop_duplicates(["measure", "scenario", "test"]).set_index(["measure", "scenario", "test"])
    for row in needed.itertuples(index=False):
        pilot = first.loc[(row.measure, row.scenario, row.test)]
        lines.append(f"| {row.measure} | {row.scenario} | {row.test} | {pilot['pilot_F']:.2f} | "
                     f"{pilot['pilot_partial_eta2']:.3f} | {_n(row.n_80)} | {_n(row.n_90)} |")
    if n_pilots < SMALL_PILOT:
        lines += ["", f"**Only {n_pilots} pilot participants**: resampling so few people under-represents the "
                      "spread of a population, and the power estimates are too optimistic. Run more "
                      f"(`steakhouse pilot --participants {SMALL_PILOT * 2}` or more)."]
    if short:
        lines += ["", "Not simulated (too few complete pilot participants):", "",
                  *(f"- {measure}: {reason}" for measure, reason in short.items())]
    lines += ["", "Power at each n: `power.csv`" + ("; plot: `power.png`." if plotted else ".")]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def _n(value: object) -> str:
    return "beyond the grid" if value is None or pd.isna(value) else str(int(value))  # type: ignore[call-overload]
