"""The FOV effect on kitchens nobody tuned on (docs/domain.md §5; the targets of docs/benchmarks.md).

Kitchens come from :mod:`planner.layout_gen` (``steakhouse layout generate``): generator seeds below 1000 are
the *tuning* set (the generator's own choices, e.g. the doorway width, were made looking at seeds 0–99 only);
the report uses seeds 1000 and up, one kitchen per seed, × ``--sim-seeds`` simulation seeds; the shipped
kitchens × ``--shipped-seeds`` seeds; and the reference's simulation kitchens (``reference_kitchens/``, converted
from its configs) × ``--reference-seeds`` seeds. Every trial is one row of ``steakhouse simulate``'s ``trials.csv``
(:func:`planner.experiment.run_spec`, the simulated FOV-limited human, the same human random stream per
seed for every robot, so trials are paired), run in ``--jobs`` worker processes and appended to
``OUT/trials.csv`` as it finishes, so a cut-short run still leaves every finished trial.

The robots model the paper's person (120°, KB delay ``--model-delay``, default 3). ``--person ANGLE,DELAY,RANDOM``
plays them with a simulated person who differs from that model (:class:`planner.partner.Person`: another view,
another delay, a share of random actions): the robustness comparisons.

Printed: per group (reference, shipped; generated, overall and per style; each reference and shipped kitchen
too) the paired FOV-aware vs baseline comparison: mean ticks, % change with its 95 % t interval (the paired
differences' interval over the baseline's mean), paired t-test and Wilcoxon p, and unfinished trials per robot.

Run (from the repository root)::

    .venv/bin/python benchmarks/planner/generated.py --out results/generated --jobs 2
    .venv/bin/python benchmarks/planner/generated.py --generator-seeds 1000-1099 --sim-seeds 2 --shipped-seeds 10 \
        --reference-seeds 30 --person 90,3,0 --out results/angle90 --jobs 2
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

import numpy as np
from scipy import stats

from planner.experiment import COLUMNS, TrialSpec, paired_comparison, run_spec
from planner.layout_gen import STYLES, generate_named
from planner.partner import Person
from planner.perception import FOV_ANGLE, KB_DELAY
from study_config import layout_names, load_layout

REFERENCE_KITCHENS = Path(__file__).resolve().parent / "reference_kitchens"
"""The reference's simulation kitchens (its ``all.csv`` levels; provenance in the folder's README)."""


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


def reference_kitchens() -> tuple[str, ...]:
    """The paths of the reference's simulation kitchens."""
    return tuple(str(p) for p in sorted(REFERENCE_KITCHENS.glob("*.layout")))


def trial_specs(kitchens: list[str], shipped: tuple[str, ...], robots: list[str], sim_seeds: int,
                shipped_seeds: int, reference: tuple[str, ...] = (), reference_seeds: int = 0,
                person: Person | None = None, model_delay: int = KB_DELAY) -> list[TrialSpec]:
    """In ``sim_seeds`` blocks, so that a cut-short run has covered every kitchen evenly: block ``b`` is
    every generated kitchen with seed ``b``, then the shipped and the reference kitchens with their ``b``-th share
    of their seeds; each (kitchen, seed) with all robots together (complete pairs)."""
    blocks = max(sim_seeds, 1)
    shipped_share, reference_share = -(-shipped_seeds // blocks), -(-reference_seeds // blocks)
    specs = []

    def spec(kitchen: str, robot: str, seed: int) -> TrialSpec:
        return TrialSpec(load_layout(kitchen), robot, seed, FOV_ANGLE, model_delay, person=person)

    for b in range(blocks):
        if b < sim_seeds:
            specs += [spec(k, r, b) for k in kitchens for r in robots]
        seeds = range(b * shipped_share, min((b + 1) * shipped_share, shipped_seeds))
        specs += [spec(k, r, s) for s in seeds for k in shipped for r in robots]
        seeds = range(b * reference_share, min((b + 1) * reference_share, reference_seeds))
        specs += [spec(k, r, s) for s in seeds for k in reference for r in robots]
    return specs


def group_of(row: dict[str, Any]) -> tuple[str, str]:
    """(``generated``, ``reference`` or ``shipped``, style or kitchen name) of a trial row."""
    name = Path(str(row["layout"])).stem
    tail = name.rsplit("_", 1)[-1]
    if name.startswith("gen_") and tail in STYLES:
        return "generated", tail
    return ("reference" if (REFERENCE_KITCHENS / f"{name}.layout").exists() else "shipped"), name


GROUP_ORDER = ("reference", "shipped", "generated")


def change_interval(part: list[dict[str, Any]], keys: set[tuple[str, str]], robot: str = "fov_aware",
                    reference: str = "baseline") -> tuple[float, float]:
    """The 95 % t interval of the mean paired difference of ticks, in % of the reference robot's mean."""
    ticks = {(r["layout"], r["seed"], r["robot"]): float(r["ticks"]) for r in part}
    d = np.array([ticks[(k, s, robot)] - ticks[(k, s, reference)] for k, s in sorted(keys)])
    base = float(np.mean([ticks[(k, s, reference)] for k, s in keys]))
    half = float(stats.t.ppf(0.975, len(d) - 1) * d.std(ddof=1) / np.sqrt(len(d))) if len(d) > 1 else float("nan")
    return 100 * (d.mean() - half) / base, 100 * (d.mean() + half) / base


def table(rows: list[dict[str, Any]], robots: list[str], robot: str = "fov_aware") -> str:
    """Paired ``robot`` vs baseline per group (and per reference and shipped kitchen), and unfinished trials per
    robot."""
    groups: dict[str, list[dict[str, Any]]] = {}
    for row in rows:
        kind, sub = group_of(row)
        groups.setdefault(kind, []).append(row)
        groups.setdefault(f"{kind}:{sub}", []).append(row)
    head = (f"{'group':<26}{'kitchens':>9}{'pairs':>7}{robot[:18]:>19}{'baseline':>10}{'change':>9}"
            f"{'95% interval':>18}{'t p':>10}{'Wilcoxon p':>12}  unfinished per robot")
    lines = [head, "-" * len(head)]
    for name in sorted(groups, key=lambda g: (GROUP_ORDER.index(g.split(":")[0]), ":" in g, g)):
        part = groups[name]
        kitchens = len({r["layout"] for r in part})
        unfinished = ", ".join(f"{rb} {sum(1 for r in part if r['robot'] == rb and not int(r['finished']))}"
                               f"/{sum(1 for r in part if r['robot'] == rb)}" for rb in robots)
        cmp = paired_comparison(part, robot)
        if cmp is None:
            lines.append(f"{name:<26}{kitchens:>9}{'-':>7}{'':>78}  {unfinished}")
            continue
        keys = {(r["layout"], r["seed"]) for r in part if r["robot"] == robot} & \
            {(r["layout"], r["seed"]) for r in part if r["robot"] == "baseline"}

        def mean(robot: str, part: list[dict[str, Any]] = part, keys: set[tuple[str, str]] = keys) -> float:
            ticks = [float(r["ticks"]) for r in part if r["robot"] == robot and (r["layout"], r["seed"]) in keys]
            return sum(ticks) / len(ticks)

        low, high = change_interval(part, keys, robot)
        lines.append(f"{name:<26}{kitchens:>9}{cmp.pairs:>7}{mean(robot):>19.1f}{mean('baseline'):>10.1f}"
                     f"{cmp.mean_change_pct:>+8.1f}%{f'[{low:+.1f}, {high:+.1f}]':>18}{cmp.t_p:>10.3g}"
                     f"{cmp.wilcoxon_p:>12.3g}  {unfinished}")
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
    parser.add_argument("--reference-seeds", type=int, default=0,
                        help="seeds per reference simulation kitchen (reference_kitchens/; 0: none)")
    parser.add_argument("--person", default=None, metavar="ANGLE,DELAY,RANDOM",
                        help="the simulated person, when it differs from the robots' model (e.g. 90,3,0)")
    parser.add_argument("--model-delay", type=int, default=KB_DELAY, help="the robots' model of the KB delay")
    parser.add_argument("--robots", default="fov_aware,baseline")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--out", required=True, type=Path)
    parser.add_argument("--table-only", action="store_true", help="print the table of OUT/trials.csv")
    args = parser.parse_args(argv)
    robots = args.robots.split(",")
    csv_path = args.out / "trials.csv"
    person = None
    if args.person is not None:
        try:
            angle, delay, share = args.person.split(",")
            person = Person(float(angle), int(delay), float(share))
        except ValueError:
            parser.error(f"--person {args.person!r}: expected ANGLE,DELAY,RANDOM, e.g. 90,3,0")
    if not args.table_only:
        kitchens = write_kitchens(seed_range(args.generator_seeds), args.out / "kitchens") if args.sim_seeds else []
        specs = trial_specs(kitchens, layout_names() if args.shipped_seeds else (), robots, args.sim_seeds,
                            args.shipped_seeds, reference_kitchens(), args.reference_seeds, person,
                            args.model_delay)
        done = {(r["layout"], r["robot"], int(r["seed"])) for r in read_rows(csv_path)} if csv_path.exists() else set()
        for _ in run(specs, args.jobs, csv_path, done):
            pass
    rows = read_rows(csv_path)
    print(f"generator seeds {args.generator_seeds} × sim seeds 0–{args.sim_seeds - 1}; shipped kitchens × seeds "
          f"0–{args.shipped_seeds - 1}; reference kitchens × seeds 0–{args.reference_seeds - 1}; robots model 120°, "
          f"delay {args.model_delay}; simulated person {args.person or 'as modelled'}; {len(rows)} trials in "
          f"{csv_path}")
    for robot in robots:
        if robot != "baseline":
            print(table(rows, robots, robot))
    return 0


if __name__ == "__main__":
    sys.exit(main())
