"""Planner latency and quality, measured on this machine (docs/domain.md §5; the targets are in the README).

1. Decision time p50 / p95 / p99 per kitchen and planner, one process pinned to one core when possible,
   over full simulated trials with the FOV-limited simulated human.
2. The paper's simulation table: every shipped kitchen × ``--seeds`` seeds, FOV-aware vs baseline, with
   the paired difference (run through ``steakhouse simulate``'s own code).
"""

from __future__ import annotations

import argparse
import os
import sys

import numpy as np


def main(argv: list[str] | None = None) -> int:
    from planner.experiment import TrialSpec, run_spec, summarize_trials
    from planner.planner_config import PlannerConfig
    from planner.play import run_trial
    from planner.robots import make_robot
    from planner.rules import Rules
    from study_config import layout_names, load_layout

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=10)
    parser.add_argument("--latency-seeds", type=int, default=3)
    parser.add_argument("--robots", default="fov_aware,baseline,no_rollout")
    args = parser.parse_args(argv)
    if hasattr(os, "sched_setaffinity"):
        os.sched_setaffinity(0, {sorted(os.sched_getaffinity(0))[0]})
    robots = args.robots.split(",")
    print(f"decision time in ms over {args.latency_seeds} trials per kitchen (one core)")
    print(f"{'kitchen':<10}{'planner':<12}{'p50':>8}{'p95':>8}{'p99':>8}{'max':>8}{'decisions':>11}")
    worst = dict.fromkeys(robots, 0.0)
    for name in layout_names():
        layout = load_layout(name)
        for robot_name in robots:
            times: list[float] = []
            for seed in range(args.latency_seeds):
                robot = make_robot(robot_name, layout, Rules(), PlannerConfig())
                times.extend(run_trial(layout, seed, robot=robot).decision_ms)
            t = np.array(times)
            p50, p95, p99 = np.percentile(t, [50, 95, 99])
            worst[robot_name] = max(worst[robot_name], float(p99))
            print(f"{name:<10}{robot_name:<12}{p50:8.2f}{p95:8.2f}{p99:8.2f}{t.max():8.2f}{len(t):11d}")
    for robot_name, p99 in worst.items():
        print(f"worst p99 {robot_name}: {p99:.2f} ms")
    specs = [TrialSpec(load_layout(n), r, s) for n in layout_names() for r in ("fov_aware", "baseline")
             for s in range(args.seeds)]
    rows = [run_spec(spec) for spec in specs]
    print(summarize_trials(rows))
    return 0


if __name__ == "__main__":
    sys.exit(main())
