"""The paper's two robot behaviours on our robots (docs/domain.md §6, "Behaviours").

For each robot × kitchen × seed, one simulated trial with the FOV-limited simulated human (the same human random
stream per seed for every robot, so trials are paired): behaviour 1 (a pickup shown to the person for
``kb_delay`` consecutive ticks), behaviour 2 (share of a dish trip's ticks in the person's view), the robot
component of the KB gap (% of ticks the person's KB is wrong about what the robot holds; split into lag, unseen
and stale, :func:`planner.behaviours.hands_gap`), where the KB places the robot (``place_cells``: how many cells
from where it is, on average; ``place_wrong``: % of ticks elsewhere), the paper's KB gap (``kb_freq`` = its
``kb_diff_freq``, % of ticks with a gap; ``kb_avg`` = ``kb_diff_avg``, the mean gap over those ticks;
:mod:`planner.summary`), the person's share of the deliveries (``p_deliv``) and ticks (:mod:`planner.behaviours`).
Kitchens: shipped ones by name (``--shipped``, default the paper's two study kitchens) and generated ones by
generator seed (``--generator-seeds``; tune only on seeds < 1000, report on seeds ≥ 1000, as ``generated.py``
does). Rows are appended to ``OUT/trials.csv`` as trials finish.

Printed per group (each shipped kitchen; generated kitchens together) and robot: the pooled rates, then each
robot against the baseline over paired seeds: mean difference of the per-trial values with a 95 % t interval
and the paired t-test p (ticks also Wilcoxon).

    .venv/bin/python benchmarks/planner/behaviours.py --seeds 30 --out results/behaviours --jobs 2
    .venv/bin/python benchmarks/planner/behaviours.py --shipped "" --generator-seeds 0-19 --seeds 3 --out DIR
    .venv/bin/python benchmarks/planner/behaviours.py --out DIR --table-only

``--set name=value`` overrides a :class:`planner.planner_config.PlannerConfig` field for every shipped robot
(tuning). ``--robots`` takes any installed robot, plug-ins too (``steakhouse robots``); each plays guarded
(:class:`planner.robot_guard.GuardedRobot`): a trial whose robot failed is listed at the end and the run exits 1.
"""

from __future__ import annotations

import argparse
import csv
import statistics
import sys
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, fields
from pathlib import Path
from typing import Any

import numpy as np
from scipy import stats

from planner import robot_catalog
from planner.behaviours import Frame, frame_of
from planner.experiment import GAP_PARTS, behaviour_columns, flagged_lines
from planner.layout import Layout
from planner.layout_gen import GenerationError, KitchenRequest, generate_named, parse_size
from planner.perception import FOV_ANGLE, KB_DELAY
from planner.planner_config import PlannerConfig
from planner.play import TrialResult, TrialSettings, run_trial
from planner.robot_api import Person
from planner.robot_catalog import RobotSetup
from planner.robot_guard import GuardedRobot
from planner.rules import Rules
from planner.state import WorldState, initial_state
from planner.step import step
from study_config import load_layout

COLUMNS = ("kitchen", "robot", "seed", "ticks", "finished", "holdings", "shown", "trips", "trip_share_sum",
           "robot_gap_pct", "gap_lag_pct", "gap_unseen_pct", "gap_stale_pct", "robot_place_cells",
           "robot_place_wrong_pct", "kb_gap_mean", "kb_diff_freq", "kb_diff_avg", "person_deliveries",
           "robot_deliveries", "robot_faults", "robot_fault")


@dataclass(frozen=True, slots=True)
class Spec:
    kitchen: str
    robot: str
    seed: int
    overrides: tuple[tuple[str, str], ...] = ()


def kitchen_layout(name: str) -> Layout:
    """A shipped kitchen by name, or ``gen_<seed>`` (``gen_<seed>_<W>x<H>``: of that grid size) for a generated
    one."""
    if name.startswith("gen_"):
        _, seed, *size = name.split("_")
        return generate_named(int(seed), KitchenRequest(size=parse_size(size[0]) if size else None))
    return load_layout(name)


def config_values(overrides: tuple[tuple[str, str], ...]) -> dict[str, Any]:
    """``--set`` values as the :class:`PlannerConfig` fields take them."""
    types = {f.name: f.type for f in fields(PlannerConfig)}
    values: dict[str, Any] = {}
    for name, text in overrides:
        kind = types[name]
        values[name] = (text.lower() in ("1", "true", "yes")) if kind in (bool, "bool") else (
            int(text) if kind in (int, "int") else float(text) if kind in (float, "float") else text)
    return values


def robot_of(name: str, layout: Layout, rules: Rules, overrides: tuple[tuple[str, str], ...] = ()) -> GuardedRobot:
    """The installed robot ``name`` for a trial with the paper's person (``--set`` changes a shipped one), guarded."""
    values = config_values(overrides) if robot_catalog.entry(name).shipped else {}
    setup = RobotSetup(Person(FOV_ANGLE, KB_DELAY), tuple(values.items()))
    return GuardedRobot(robot_catalog.build(name, layout, rules, setup))


def run_one(spec: Spec) -> dict[str, object]:
    layout = kitchen_layout(spec.kitchen)
    rules = Rules()
    robot = robot_of(spec.robot, layout, rules, spec.overrides)
    result = run_trial(layout, spec.seed, TrialSettings(FOV_ANGLE, KB_DELAY, rules), robot=robot)
    return {"kitchen": spec.kitchen, "robot": spec.robot, "seed": spec.seed, "ticks": result.ticks,
            "finished": int(result.finished), **behaviour_columns(result),
            "kb_gap_mean": round(result.kb_gap_mean, 4), "kb_diff_freq": round(result.kb_diff_freq, 2),
            "kb_diff_avg": "" if result.kb_diff_avg is None else round(result.kb_diff_avg, 4),
            "person_deliveries": result.work.deliveries.person, "robot_deliveries": result.work.deliveries.robot,
            "robot_faults": robot.faults, "robot_fault": robot.first_fault or ""}


def seed_range(text: str) -> range:
    low, _, high = text.partition("-")
    return range(int(low), int(high or low) + 1)


def trial_arguments(parser: argparse.ArgumentParser, robots: str) -> None:
    """The trials a benchmark of this folder plays: kitchens, seeds, robots and worker processes."""
    parser.add_argument("--shipped", default="none_3,mid_2", help="shipped kitchens, comma separated ('' for none)")
    parser.add_argument("--generator-seeds", default="", help="generated kitchens, e.g. 1000-1019 (tune on < 1000)")
    parser.add_argument("--generator-size", default=None, metavar="WxH", type=size_text,
                        help="the generated kitchens' grid size, walls included (default: drawn per kitchen)")
    parser.add_argument("--seeds", type=int, default=30, help="simulation seeds 0..N-1 per kitchen")
    parser.add_argument("--robots", default=robots)
    parser.add_argument("--jobs", type=int, default=2)


def size_text(text: str) -> str:
    """``--generator-size``: a ``WxH`` grid size, as ``steakhouse layout generate --size`` takes it."""
    try:
        parse_size(text)
    except GenerationError as error:
        raise argparse.ArgumentTypeError(str(error)) from None
    return text


def kitchens_of(args: argparse.Namespace) -> list[str]:
    """The kitchens :func:`trial_arguments` named: shipped ones by name, generated ones as ``gen_<seed>``."""
    kitchens = [k for k in args.shipped.split(",") if k]
    if args.generator_seeds:
        size = f"_{args.generator_size}" if args.generator_size else ""
        kitchens += [f"gen_{s}{size}" for s in seed_range(args.generator_seeds)]
    return kitchens


@dataclass(frozen=True, slots=True)
class Replayed:
    """One trial as played, tick by tick: ``worlds[i]`` the world after tick ``i + 1``, ``frames[i]`` its frame."""

    layout: Layout
    result: TrialResult
    worlds: list[WorldState]
    frames: list[Frame]


def replayed(kitchen: str, robot_name: str, seed: int) -> Replayed:
    """A trial of ``robot_name`` (the default planner) with the simulated person, and its worlds replayed."""
    layout = kitchen_layout(kitchen)
    rules = Rules()
    result = run_trial(layout, seed, TrialSettings(rules=rules),
                       robot=robot_of(robot_name, layout, rules), record=True)
    world = initial_state(layout, rules)
    worlds: list[WorldState] = []
    frames: list[Frame] = []
    for h_action, r_action in result.actions:
        world, events = step(layout, world, {"human": h_action, "robot": r_action}, rules)
        worlds.append(world)
        frames.append(frame_of(layout, world, events, FOV_ANGLE))
    return Replayed(layout, result, worlds, frames)


def trial_values(row: dict[str, Any]) -> dict[str, float | None]:
    """Per-trial values compared between robots: behaviour rates (None without a holding / a trip), % and ticks
    (the robot gap's parts None in rows written before they were measured)."""
    holdings, trips = int(row["holdings"]), int(row["trips"])
    parts = {f"gap_{part}": float(row[f"gap_{part}_pct"]) if row.get(f"gap_{part}_pct") else None
             for part in GAP_PARTS}
    place = {name: float(row[column]) if row.get(column) else None
             for name, column in (("place_cells", "robot_place_cells"), ("place_wrong", "robot_place_wrong_pct"))}
    delivered = int(row.get("person_deliveries") or 0) + int(row.get("robot_deliveries") or 0)
    return {"b1": int(row["shown"]) / holdings if holdings else None,
            "b2": float(row["trip_share_sum"]) / trips if trips else None,
            "robot_gap": float(row["robot_gap_pct"]), **parts, **place,
            "kb_freq": float(row["kb_diff_freq"]) if row.get("kb_diff_freq") else None,
            "kb_avg": float(row["kb_diff_avg"]) if row.get("kb_diff_avg") else None,
            "p_deliv": int(row["person_deliveries"]) / delivered if delivered else None,
            "ticks": float(row["ticks"])}


def paired(a: list[float], b: list[float]) -> str:
    """``mean difference [95 % CI] p`` of paired values (a − b)."""
    if len(a) < 2:
        return "-"
    d = np.array(a) - np.array(b)
    mean, sem = float(d.mean()), float(d.std(ddof=1) / np.sqrt(len(d)))
    half = float(stats.t.ppf(0.975, len(d) - 1)) * sem
    p = float(stats.ttest_rel(a, b).pvalue) if np.any(d != 0) else 1.0
    return f"{mean:+.3g} [{mean - half:+.3g}, {mean + half:+.3g}] p={p:.2g} n={len(d)}"


def gap_parts(rows: list[dict[str, Any]]) -> str:
    """``   lag + unseen + stale`` (mean % of ticks) of rows that have them, else nothing."""
    if not all(r.get(f"gap_{part}_pct") for r in rows for part in GAP_PARTS):
        return ""
    means = [statistics.mean(float(r[f"gap_{part}_pct"]) for r in rows) for part in GAP_PARTS]
    return "   " + " + ".join(f"{m:.1f}" for m in means)


def table(rows: list[dict[str, Any]]) -> str:
    groups: dict[str, list[dict[str, Any]]] = {}
    for row in rows:
        groups.setdefault("generated" if str(row["kitchen"]).startswith("gen_") else str(row["kitchen"]),
                          []).append(row)
    robots = sorted({str(r["robot"]) for r in rows}, key=lambda r: (r != "fov_aware", r == "baseline", r))
    lines = []
    for name in sorted(groups, key=lambda g: (g == "generated", g)):
        part = groups[name]
        lines.append(f"== {name}: {len({r['kitchen'] for r in part})} kitchen(s), "
                     f"seeds {len({r['seed'] for r in part})}")
        lines.append(f"{'robot':<19}{'trials':>7}{'unf.':>6}{'b1 shown':>16}{'b2 trip share':>20}"
                     f"{'robot gap %':>13}{'kb_diff freq':>13}{'avg':>7}{'ticks':>9}"
                     "   robot gap = lag + unseen + stale")
        for robot in robots:
            mine = [r for r in part if r["robot"] == robot]
            if not mine:
                continue
            holdings = sum(int(r["holdings"]) for r in mine)
            shown = sum(int(r["shown"]) for r in mine)
            trips = sum(int(r["trips"]) for r in mine)
            share = sum(float(r["trip_share_sum"]) for r in mine)
            b1 = f"{shown / holdings:.2f} ({holdings})" if holdings else "-"
            b2 = f"{share / trips:.2f} ({trips} trips)" if trips else "-"
            freq = [float(r["kb_diff_freq"]) for r in mine if r.get("kb_diff_freq")]
            avg = [float(r["kb_diff_avg"]) for r in mine if r.get("kb_diff_avg")]
            lines.append(f"{robot:<19}{len(mine):>7}{sum(1 for r in mine if not int(r['finished'])):>6}{b1:>16}"
                         f"{b2:>20}{statistics.mean(float(r['robot_gap_pct']) for r in mine):>13.1f}"
                         f"{statistics.mean(freq) if freq else float('nan'):>13.1f}"
                         f"{statistics.mean(avg) if avg else float('nan'):>7.3f}"
                         f"{statistics.mean(float(r['ticks']) for r in mine):>9.1f}{gap_parts(mine)}")
        base = {(r["kitchen"], r["seed"]): trial_values(r) for r in part if r["robot"] == "baseline"}
        for robot in robots:
            if robot == "baseline":
                continue
            values = {(r["kitchen"], r["seed"]): trial_values(r) for r in part if r["robot"] == robot}
            keys = sorted(set(values) & set(base))
            if not keys:
                continue
            lines.append(f"  {robot} − baseline (paired per kitchen × seed, mean [95% CI]):")
            for measure_name in ("b1", "b2", "robot_gap", *(f"gap_{part}" for part in GAP_PARTS), "place_cells",
                                 "place_wrong", "kb_freq", "kb_avg", "p_deliv", "ticks"):
                pairs = [(values[k][measure_name], base[k][measure_name]) for k in keys
                         if values[k][measure_name] is not None and base[k][measure_name] is not None]
                if not pairs:
                    continue
                text = paired([float(a) for a, _ in pairs], [float(b) for _, b in pairs])  # type: ignore[arg-type]
                if measure_name == "ticks" and len(pairs) > 1 and any(a != b for a, b in pairs):
                    ticks_base = statistics.mean(float(b) for _, b in pairs)  # type: ignore[arg-type]
                    diff = statistics.mean(float(a) - float(b) for a, b in pairs)  # type: ignore[arg-type]
                    text += (f" ({100 * diff / ticks_base:+.1f}%, Wilcoxon p="
                             f"{stats.wilcoxon([a for a, _ in pairs], [b for _, b in pairs]).pvalue:.2g})")
                lines.append(f"    {measure_name:<10} {text}")
    return "\n".join(lines)


def read_rows(path: Path) -> list[dict[str, Any]]:
    with path.open(newline="") as handle:
        return list(csv.DictReader(handle))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    trial_arguments(parser, "fov_aware,baseline")
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                        help="a PlannerConfig field for every robot (repeatable)")
    parser.add_argument("--out", required=True, type=Path)
    parser.add_argument("--table-only", action="store_true")
    args = parser.parse_args(argv)
    names = {f.name for f in fields(PlannerConfig)}
    overrides = []
    for item in args.set:
        name, sep, value = item.partition("=")
        if not sep or name not in names:
            parser.error(f"--set {item!r}: expected NAME=VALUE with NAME a PlannerConfig field")
        overrides.append((name, value))
    for robot in args.robots.split(","):
        try:
            robot_catalog.entry(robot)
        except robot_catalog.RobotUnavailable as exc:
            parser.error(str(exc))
    csv_path = args.out / "trials.csv"
    if not args.table_only:
        kitchens = kitchens_of(args)
        done = ({(r["kitchen"], r["robot"], int(r["seed"])) for r in read_rows(csv_path)}
                if csv_path.exists() else set())
        specs = [Spec(k, r, s, tuple(overrides)) for s in range(args.seeds) for k in kitchens
                 for r in args.robots.split(",") if (k, r, s) not in done]
        args.out.mkdir(parents=True, exist_ok=True)
        fresh = not csv_path.exists()
        with csv_path.open("a", newline="") as handle, ProcessPoolExecutor(max_workers=args.jobs) as pool:
            writer = csv.DictWriter(handle, fieldnames=COLUMNS)
            if fresh:
                writer.writeheader()
            for i, row in enumerate(pool.map(run_one, specs, chunksize=1), 1):
                writer.writerow(row)
                handle.flush()
                if i % 20 == 0 or i == len(specs):
                    print(f"{i}/{len(specs)} trials", file=sys.stderr, flush=True)
    rows = read_rows(csv_path)
    print(f"{len(rows)} trials in {csv_path}" + (f"; overrides {' '.join(args.set)}" if args.set else ""))
    print(table(rows))
    flagged = flagged_lines([{**r, "layout": r["kitchen"]} for r in rows])
    print("\n".join(flagged))
    return 1 if flagged else 0


if __name__ == "__main__":
    sys.exit(main())
