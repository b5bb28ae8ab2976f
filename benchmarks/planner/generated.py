"""The FOV effect on kitchens nobody tuned on (docs/domain.md §5).

Kitchens come from :mod:`planner.layout_gen` (``steakhouse layout generate``): generator seeds 0–99 are
the *tuning* set (the generator's own choices, e.g. the doorway width, were made looking at them only);
the report uses seeds 1000–1099, one kitchen per seed, × ``--sim-seeds`` simulation seeds, and the shipped
kitchens × ``--shipped-seeds`` seeds. Every trial is one row of ``steakhouse simulate``'s ``trials.csv``
(:func:`planner.experiment.run_spec`, the simulated FOV-limited human, the same human random stream per
seed for every robot, so trials are paired), run in ``--jobs`` worker processes and appended to
``OUT/trials.csv`` as it finishes, so a cut-short run still leaves every finished trial.

Printed: per group (shipped; generated, overall and per style) the paired FOV-aware vs baseline
comparison (mean ticks, % change, paired t-test and Wilcoxon p) and unfinished trials per robot.

Run (from the repository root)::

    .venv/bin/python benchmarks/planner/generated.py --out results/generated --jobs 2
    .venv/bin/python benchmarks/planner/generated.py --out results/generated --table-only
"""

from __future__ import annotations

import argparse
import csv
import sys
from collections.abc import Iterator
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from typing import Any

from planner.experiment import COLUMNS, TrialSpec, paired_comparison, run_spec
from planner.layout_gen import STYLES, generate_named
from study_config import layout_names, load_layout


def seed_range(text: str) -> range:
    """``"1000-1099"`` → ``range(1000, 1100)``; ``"7"`` → ``range(7, 8)``."""
    low, _, high = text.partition("-")
    return range(int(low), int(high or low) + 1)


def write_kitchens(seeds: range, folder: Path) -> list[str]:
    """The generated kitchens as files (what ``steakhouse layout generate`` writes); their paths."""
    folder.mkdir(parents=True, exist_ok=True)
    paths = []
    for seed in seeds:
        layout = generate_named(seed)
        path = folder / f"{layout.name}.layout"
        path.write_text(layout.text(), encoding="utf-8")
        paths.append(str(path))
    return paths


def trial_specs(kitchens: list[str], shipped: tuple[str, ...], robots: list[str], sim_seeds: int,
                shipped_seeds: int) -> list[TrialSpec]:
    """In ``sim_seeds`` blocks, so that a cut-short run has covered every kitchen evenly: block ``b`` is
    every generated kitchen with seed ``b``, then the shipped kitchens with their ``b``-th share of the
    shipped seeds; each (kitchen, seed) with all robots together (complete pairs)."""
    share = -(-shipped_seeds // max(sim_seeds, 1))
    specs = []
    for b in range(max(sim_seeds, 1)):
        if b < sim_seeds:
            specs += [TrialSpec(load_layout(k), r, b) for k in kitchens for r in robots]
        seeds = range(b * share, min((b + 1) * share, shipped_seeds))
        specs += [TrialSpec(load_layout(k), r, s) for s in seeds for k in shipped for r in robots]
    return specs


def group_of(row: dict[str, Any]) -> tuple[str, str]:
    """(``generated`` or ``shipped``, style or kitchen name) of a trial row."""
    name = Path(str(row["layout"])).stem
    tail = name.rsplit("_", 1)[-1]
    style = tail if name.startswith("gen_") and tail in STYLES else None
    return ("generated", style) if style is not None else ("shipped", name)


def table(rows: list[dict[str, Any]], robots: list[str]) -> str:
    """Paired FOV-aware vs baseline per group, and unfinished trials per robot."""
    groups: dict[str, list[dict[str, Any]]] = {}
    for row in rows:
        kind, sub = group_of(row)
        groups.setdefault(kind, []).append(row)
        if kind == "generated":
            groups.setdefault(f"generated:{sub}", []).append(row)
    head = (f"{'group':<22}{'kitchens':>9}{'pairs':>7}{'fov_aware':>11}{'baseline':>10}{'change':>9}"
            f"{'t p':>10}{'Wilcoxon p':>12}  unfinished per robot")
    lines = [head, "-" * len(head)]
    for name in sorted(groups, key=lambda g: (not g.startswith("shipped"), g)):
        part = groups[name]
        kitchens = len({r["layout"] for r in part})
        unfinished = ", ".join(f"{rb} {sum(1 for r in part if r['robot'] == rb and not int(r['finished']))}"
                               f"/{sum(1 for r in part if r['robot'] == rb)}" for rb in robots)
        cmp = paired_comparison(part)
        if cmp is None:
            lines.append(f"{name:<22}{kitchens:>9}{'-':>7}{'':>52}  {unfinished}")
            continue
        keys = {(r["layout"], r["seed"]) for r in part if r["robot"] == "fov_aware"} & \
            {(r["layout"], r["seed"]) for r in part if r["robot"] == "baseline"}

        def mean(robot: str, part: list[dict[str, Any]] = part, keys: set[tuple[str, str]] = keys) -> float:
            ticks = [float(r["ticks"]) for r in part if r["robot"] == robot and (r["layout"], r["seed"]) in keys]
            return sum(ticks) / len(ticks)

        lines.append(f"{name:<22}{kitchens:>9}{cmp.pairs:>7}{mean('fov_aware'):>11.1f}{mean('baseline'):>10.1f}"
                     f"{cmp.mean_change_pct:>+8.1f}%{cmp.t_p:>10.3g}{cmp.wilcoxon_p:>12.3g}  {unfinished}")
    return "\n".join(lines)


def read_rows(path: Path) -> list[dict[str, Any]]:
    with path.open(newline="") as handle:
        return list(csv.DictReader(handle))


def run(specs: list[TrialSpec], jobs: int, out: Path, done: set[tuple[str, str, int]]) -> Iterator[dict[str, object]]:
    """Run the specs not yet in ``done`` and append each row to ``out`` as it finishes."""
    todo = [s for s in specs if (s.layout.name, s.robot, s.seed) not in done]
    fresh = not out.exists()
    if not fresh:
        with out.open(newline="") as handle:
            header = tuple(next(csv.reader(handle), ()))
        if header != COLUMNS:
            raise SystemExit(f"{out}: written with other columns ({', '.join(header)}); use another --out")
    with out.open("a", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=COLUMNS)
        if fresh:
            writer.writeheader()
        with ProcessPoolExecutor(max_workers=jobs) as pool:
            for i, row in enumerate(pool.map(run_spec, todo, chunksize=1), 1):
                writer.writerow(row)
                handle.flush()
                if i % 50 == 0 or i == len(todo):
                    print(f"{i}/{len(todo)} trials", file=sys.stderr, flush=True)
                yield row


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--generator-seeds", default="1000-1099", help="report seeds (tuning set: 0-99)")
    parser.add_argument("--sim-seeds", type=int, default=5)
    parser.add_argument("--shipped-seeds", type=int, default=30)
    parser.add_argument("--robots", default="fov_aware,baseline")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--out", required=True, type=Path)
    parser.add_argument("--table-only", action="store_true", help="print the table of OUT/trials.csv")
    args = parser.parse_args(argv)
    robots = args.robots.split(",")
    csv_path = args.out / "trials.csv"
    if not args.table_only:
        kitchens = write_kitchens(seed_range(args.generator_seeds), args.out / "kitchens")
        specs = trial_specs(kitchens, layout_names(), robots, args.sim_seeds, args.shipped_seeds)
        done = {(r["layout"], r["robot"], int(r["seed"])) for r in read_rows(csv_path)} if csv_path.exists() else set()
        for _ in run(specs, args.jobs, csv_path, done):
            pass
    rows = read_rows(csv_path)
    print(f"generator seeds {args.generator_seeds} × sim seeds 0–{args.sim_seeds - 1}; shipped kitchens × seeds "
          f"0–{args.shipped_seeds - 1}; {len(rows)} trials in {csv_path}")
    print(table(rows, robots))
    return 0


if __name__ == "__main__":
    sys.exit(main())
