"""Who does the work: the person's share of the deliveries and of the task steps, in the reference's VR study logs and
in our simulated trials, side by side (docs/domain.md §6, "Who does the work"; docs/benchmarks.md).

The reference's logs (``vr_logs.py`` reads them from the fetched repository; participants 5, 11 and 12 left out as
its own analysis did) end after the first delivery, so the comparable measures are the person's share of the first
dishes and of the task steps up to the first delivery (a task step: a change of what an agent holds,
:mod:`planner.work_share`); for our trials the whole trial's shares are printed too, and the chopping and washing
presses, which the logs do not show.

Our trials: the simulated FOV-limited person (120°, KB delay 3) with each robot, on the paper's two kitchens by
default (``--shipped``) and generated ones (``--generator-seeds``; report on seeds ≥ 1000), seeds 0..N-1, paired by
seed. Per robot: the pooled shares, the mean per-trial share of deliveries with its 95 % t interval, and the paired
difference against the baseline.

    .venv/bin/python benchmarks/planner/fair_share.py /work/.mirror/SophieHsu+FOV-aware-planner/repo --seeds 30 \\
        --out results/fair --jobs 2
    .venv/bin/python benchmarks/planner/fair_share.py REFERENCE --out results/fair --table-only
"""

from __future__ import annotations

import argparse
import csv
import sys
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from scipy import stats

sys.path.insert(0, str(Path(__file__).resolve().parent))
from behaviours import kitchen_layout, kitchens_of, read_rows, trial_arguments
from vr_logs import KITCHENS, Source, log_files, work_of

from planner.perception import FOV_ANGLE, KB_DELAY
from planner.planner_config import PlannerConfig
from planner.play import TrialSettings, run_trial
from planner.robots import make_robot
from planner.rules import Rules
from planner.work_share import Tally, WorkShare

COLUMNS = ("kitchen", "robot", "seed", "ticks", "finished", "person_deliveries", "robot_deliveries", "person_steps",
           "robot_steps", "person_presses", "robot_presses", "person_steps_to_first", "robot_steps_to_first",
           "first")


@dataclass(frozen=True, slots=True)
class Spec:
    kitchen: str
    robot: str
    seed: int


def run_one(spec: Spec) -> dict[str, object]:
    """One trial's work, as a row."""
    layout, rules = kitchen_layout(spec.kitchen), Rules()
    robot = make_robot(spec.robot, layout, rules, PlannerConfig(human_angle=FOV_ANGLE, human_delay=KB_DELAY))
    result = run_trial(layout, spec.seed, TrialSettings(FOV_ANGLE, KB_DELAY, rules), robot=robot)
    work = result.work
    return {"kitchen": spec.kitchen, "robot": spec.robot, "seed": spec.seed, "ticks": result.ticks,
            "finished": int(result.finished), **row_of(work)}


def row_of(work: WorkShare) -> dict[str, object]:
    first = "human" if work.first.person else "robot" if work.first.robot else ""
    return {"person_deliveries": work.deliveries.person, "robot_deliveries": work.deliveries.robot,
            "person_steps": work.steps.person, "robot_steps": work.steps.robot,
            "person_presses": work.presses.person, "robot_presses": work.presses.robot,
            "person_steps_to_first": work.steps_to_first.person, "robot_steps_to_first": work.steps_to_first.robot,
            "first": first}


def work_of_row(row: dict[str, Any]) -> WorkShare:
    def tally(name: str) -> Tally:
        return Tally(int(row[f"person_{name}"]), int(row[f"robot_{name}"]))

    first = Tally(int(row["first"] == "human"), int(row["first"] == "robot"))
    return WorkShare(tally("deliveries"), tally("steps"), tally("presses"), tally("steps_to_first"), first)


def share(t: Tally) -> str:
    return f"{t.person_share:.3f} ({t.person}/{t.total})" if t.total else "-"


def interval(values: list[float]) -> str:
    """Mean with its 95 % t interval."""
    if len(values) < 2:
        return "-"
    a = np.array(values)
    half = float(stats.t.ppf(0.975, len(a) - 1) * a.std(ddof=1) / np.sqrt(len(a)))
    return f"{a.mean():.3f} [{a.mean() - half:.3f}, {a.mean() + half:.3f}]"


def line(source: str, kitchen: str, robot: str, n: int, work: WorkShare, extra: str = "") -> str:
    return (f"{source:<9}{kitchen:<11}{robot:<19}{n:>6}{share(work.deliveries):>18}{share(work.first):>16}"
            f"{share(work.steps_to_first):>18}{share(work.steps):>18}{share(work.presses):>16}{extra}")


def vr_table(reference: Path, include_ignored: bool) -> list[str]:
    source = Source(reference)
    works: dict[tuple[str, str], list[WorkShare]] = {}
    absent = []
    for log in log_files(source.names(), include_ignored):
        data = source.read(log.path)
        if data is None:
            absent.append(log.path)
            continue
        works.setdefault((KITCHENS[log.kitchen], log.robot), []).append(work_of(data))
    lines = [line("VR logs", kitchen, robot, len(ws), sum(ws, WorkShare()))
             for (kitchen, robot), ws in sorted(works.items())]
    every = [w for ws in works.values() for w in ws]
    lines.append(line("VR logs", "all", "both", len(every), sum(every, WorkShare())))
    if absent:
        lines.append(f"  (listed but absent from the fetched copy: {', '.join(absent)})")
    return lines


def sim_table(rows: list[dict[str, Any]]) -> list[str]:
    lines = []
    robots = sorted({str(r["robot"]) for r in rows}, key=lambda r: (r != "fov_aware", r == "baseline", r))
    kitchens = sorted({str(r["kitchen"]) for r in rows})
    groups = [(k, [r for r in rows if r["kitchen"] == k]) for k in kitchens if not k.startswith("gen_")]
    generated = [r for r in rows if str(r["kitchen"]).startswith("gen_")]
    if generated:
        groups.append(("generated", generated))
    if len(groups) > 1:
        groups.append(("all", rows))
    for kitchen, part in groups:
        base = {(r["kitchen"], r["seed"]): r for r in part if r["robot"] == "baseline"}
        for robot in robots:
            mine = [r for r in part if r["robot"] == robot]
            if not mine:
                continue
            work = sum((work_of_row(r) for r in mine), WorkShare())
            per_trial = [int(r["person_deliveries"]) / max(int(r["person_deliveries"]) + int(r["robot_deliveries"]), 1)
                         for r in mine]
            ticks = float(np.mean([float(r["ticks"]) for r in mine]))
            extra = f"{interval(per_trial):>26}{ticks:>8.1f}"
            paired = [(int(r["person_deliveries"]) / max(int(r["person_deliveries"]) + int(r["robot_deliveries"]), 1),
                       int(b["person_deliveries"]) / max(int(b["person_deliveries"]) + int(b["robot_deliveries"]), 1))
                      for r in mine if robot != "baseline" and (b := base.get((r["kitchen"], r["seed"]))) is not None]
            if paired:
                extra += f"   − baseline {interval([a - b for a, b in paired])}"
            lines.append(line("ours", kitchen, robot, len(mine), work, extra))
    return lines


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("reference", type=Path,
                        help="the fetched SophieHsu/FOV-aware-planner (bare git dir or checkout)")
    trial_arguments(parser, "fov_aware,fov_aware_showing,baseline")
    parser.add_argument("--include-ignored", action="store_true", help="also participants 5, 11, 12 of the logs")
    parser.add_argument("--out", required=True, type=Path)
    parser.add_argument("--table-only", action="store_true")
    args = parser.parse_args(argv)
    csv_path = args.out / "trials.csv"
    if not args.table_only:
        done = ({(r["kitchen"], r["robot"], int(r["seed"])) for r in read_rows(csv_path)}
                if csv_path.exists() else set())
        specs = [Spec(k, r, s) for s in range(args.seeds) for k in kitchens_of(args) for r in args.robots.split(",")
                 if (k, r, s) not in done]
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
    try:
        vr = vr_table(args.reference, args.include_ignored)
    except FileNotFoundError as exc:
        parser.error(str(exc))
    rows = read_rows(csv_path)
    print(f"the person's share (person / both): of the deliveries, of the first dishes, of the task steps up to the "
          f"first delivery and in all, of the chopping and washing presses; ours: {len(rows)} trials in {csv_path}, "
          f"the simulated person at 120°, KB delay {KB_DELAY}")
    print(f"{'source':<9}{'kitchen':<11}{'robot':<19}{'trials':>6}{'deliveries':>18}{'first dish':>16}"
          f"{'steps to 1st':>18}{'all steps':>18}{'presses':>16}{'per-trial deliveries':>26}{'ticks':>8}")
    print("\n".join(vr + sim_table(rows)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
