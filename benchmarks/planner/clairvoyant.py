"""Clairvoyant robot: an upper bound on what better prediction of the human can buy the rollout planner.

The FOV-aware robot (:mod:`planner.qmdp`, ``QmdpRobot(..., explore=True)``) predicts the simulated human
with a model: a belief over its current subtask, a modelled KB, and seeded random futures. The
*clairvoyant* robot is the same planner (same options, Q-values, exploration, yielding) except that every
lookahead rollout replays the true human exactly: it starts from the human's true KB, its true
``HumanMemory`` (current subtask, stuck counters, ...) and a copy of its true random generator, so the
robot knows what the human is doing and every random choice it will make (given the robot's moves).
Its values are therefore exact; it uses ``value_smoothing=1.0`` (no averaging across ticks, which only
blurs exact values) and ``max_subtasks=1`` (the human subtask hypothesis is ignored anyway).

On paired trials (same kitchen, same seed: the same human random stream) it compares

* ``clairvoyant`` – the robot above,
* ``fov_aware``   – the study's FOV-aware robot,
* ``baseline``    – the robot that models an omniscient human,

and prints mean ± sd ticks per kitchen and overall and the paired differences. The distance between
``fov_aware`` and ``clairvoyant`` is the part of the improvement over the baseline that better prediction
alone could still reach; what remains beyond ``clairvoyant`` needs a better planner, not a better model.

Run (from the repository root)::

    .venv/bin/python benchmarks/planner/clairvoyant.py --seeds 10
    .venv/bin/python benchmarks/planner/clairvoyant.py --layouts mid_1,side_2 --first-seed 10 --seeds 5 --json

This is a diagnostic: the clairvoyant robot reads the simulated human's hidden state, so it cannot play
with a person and no study can use it.
"""

from __future__ import annotations

import argparse
import copy
import json
import sys
from collections.abc import Sequence
from concurrent.futures import ProcessPoolExecutor
from typing import Any

import numpy as np

from planner.experiment import TrialSpec, paired_comparison, run_spec, summarize_trials
from planner.geometry import Action
from planner.human import HumanMemory
from planner.kb import KnowledgeBase
from planner.layout import Layout, LayoutError
from planner.moment import Moment
from planner.planner_config import PlannerConfig
from planner.play import TrialSettings, run_trial
from planner.qmdp import QmdpRobot
from planner.rules import Rules
from planner.state import WorldState
from planner.subtasks import Subtask
from planner.valuation import Valuation
from study_config import layout_names, load_layout

ROBOTS = ("clairvoyant", "fov_aware", "baseline")


class ClairvoyantValuation(Valuation):
    """Rollouts that replay the true human (see the module docstring)."""

    snapshot: tuple[KnowledgeBase, HumanMemory, np.random.Generator] | None = None

    def sampled(self, m: Moment, human_subtask: Subtask, robot_subtask: Subtask, prefix: tuple[Action, ...] = (),
                knowing: bool = False) -> float:
        """One rollout from the true human state (``human_subtask`` and the moment's seed are ignored); ``knowing``
        as :meth:`planner.valuation.Valuation.sampled`."""
        assert self.snapshot is not None, "see_human() must be called before decide()"
        kb, memory, human_rng = self.snapshot
        return self.rollout(m).run(m.world, kb, memory, copy.deepcopy(human_rng), robot_subtask, m.horizon, prefix,
                                   parked_for=m.human_still, knowing=knowing)


class ClairvoyantRobot(QmdpRobot):
    """The FOV-aware robot whose rollouts replay the true human (see the module docstring)."""

    def __init__(self, layout: Layout, rules: Rules, config: PlannerConfig) -> None:
        super().__init__(layout, rules, config, explore=True)

    def make_valuation(self, showing: bool) -> Valuation:
        return ClairvoyantValuation(self.layout, self.rules, self.cfg, knowing=False)

    def see_human(self, kb: KnowledgeBase, memory: HumanMemory, rng: np.random.Generator) -> None:
        """The human's true state before it acts this tick (``rng`` must be a copy; it is not consumed)."""
        assert isinstance(self.valuation, ClairvoyantValuation)
        self.valuation.snapshot = (kb, memory, rng)


def clairvoyant_trial(layout: Layout, seed: int, settings: TrialSettings = TrialSettings()) -> WorldState:
    """One trial with the clairvoyant robot (:func:`planner.play.run_trial`, the loop every robot plays);
    the final world. Before the human acts each tick, the robot is shown its KB, memory and a copy of its
    generator."""
    robot = ClairvoyantRobot(layout, settings.rules, PlannerConfig(
        human_angle=settings.angle, human_delay=settings.kb_delay, value_smoothing=1.0,
        max_subtasks=1))
    return run_trial(layout, seed, settings, robot=robot,
                     before_human=lambda kb, memory, rng: robot.see_human(kb, memory, copy.deepcopy(rng))).final


def run_one(job: tuple[str, str, int]) -> dict[str, Any]:
    """One (kitchen, robot, seed) trial as a row with ``planner.experiment``'s keys (worker processes)."""
    layout_name, robot, seed = job
    if robot != "clairvoyant":
        return run_spec(TrialSpec(load_layout(layout_name), robot, seed))  # exactly what `steakhouse simulate` runs
    rules = Rules()
    final = clairvoyant_trial(load_layout(layout_name), seed, TrialSettings(rules=rules))
    return {"layout": layout_name, "robot": robot, "seed": seed, "ticks": final.tick,
            "finished": int(final.orders_left == 0), "reward": final.score}


def comparisons(rows: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Paired differences (ratio of mean ticks over the paired trials, t-test and Wilcoxon p)."""
    out = []
    for robot, reference in (("clairvoyant", "baseline"), ("fov_aware", "baseline"), ("clairvoyant", "fov_aware")):
        c = paired_comparison(rows, robot, reference)
        if c is not None:
            out.append({"robot": robot, "reference": reference, "pairs": c.pairs,
                        "mean_ticks_change_pct": round(c.mean_change_pct, 2), "t_p": c.t_p, "wilcoxon_p": c.wilcoxon_p})
    return out


def parse_args(argv: Sequence[str] | None) -> tuple[argparse.Namespace, list[str]]:
    parser = argparse.ArgumentParser(
        prog="clairvoyant.py", description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--layouts", default="all", help="all, or comma-separated kitchen names/files")
    parser.add_argument("--seeds", type=int, default=10, help="number of seeds per kitchen (default 10)")
    parser.add_argument("--first-seed", type=int, default=0, help="seeds run from this one (default 0)")
    parser.add_argument("--jobs", type=int, default=2, help="worker processes (default 2)")
    parser.add_argument("--json", action="store_true", help="print the trials and comparisons as JSON")
    args = parser.parse_args(argv)
    if args.seeds < 1:
        parser.error("--seeds must be at least 1")
    if args.first_seed < 0:
        parser.error("--first-seed must be 0 or more")
    if args.jobs < 1:
        parser.error("--jobs must be at least 1")
    names = list(layout_names()) if args.layouts == "all" else [n.strip() for n in args.layouts.split(",") if n.strip()]
    if not names:
        parser.error("--layouts: no kitchen given")
    for name in names:
        try:
            load_layout(name)
        except LayoutError as exc:
            parser.error(f"--layouts: {exc}")
    return args, names


def main(argv: Sequence[str] | None = None) -> int:
    args, names = parse_args(argv)
    seeds = range(args.first_seed, args.first_seed + args.seeds)
    jobs = [(name, robot, seed) for name in names for seed in seeds for robot in ROBOTS]
    if args.jobs == 1:
        rows = [run_one(job) for job in jobs]
    else:
        with ProcessPoolExecutor(max_workers=args.jobs) as pool:
            rows = list(pool.map(run_one, jobs, chunksize=1))
    if args.json:
        trials = [{k: r[k] for k in ("layout", "robot", "seed", "ticks", "finished")} for r in rows]
        print(json.dumps({"seeds": [seeds.start, seeds.stop - 1], "layouts": names, "comparisons": comparisons(rows),
                          "trials": trials}, indent=2))
        return 0
    print(f"{len(names)} kitchen(s) x seeds {seeds.start}-{seeds.stop - 1}, robots: {', '.join(ROBOTS)}")
    # planner.experiment's table; its own last line (fov_aware vs baseline only) is replaced by ours below
    print("\n".join(line for line in summarize_trials(rows).splitlines() if not line.startswith("fov_aware vs ")))
    unfinished = {robot: sum(1 for r in rows if r["robot"] == robot and not r["finished"]) for robot in ROBOTS}
    print("unfinished trials: " + ", ".join(f"{robot} {n}" for robot, n in unfinished.items()))
    print("paired % change of ticks against the reference = 100 * (mean robot - mean reference) / mean reference "
          "over the same (kitchen, seed) trials (ratio of means, not mean of per-pair %):")
    for c in comparisons(rows):
        print(f"  {c['robot']:>11} vs {c['reference']:<9} {c['pairs']:4d} pairs: "
              f"{c['mean_ticks_change_pct']:+6.1f}% ticks, "
              f"paired t-test p = {c['t_p']:.4g}, Wilcoxon p = {c['wilcoxon_p']:.4g}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
