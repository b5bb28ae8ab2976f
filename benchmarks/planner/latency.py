"""Decision time of a robot planner on every shipped kitchen, this checkout against a peer checkout.

Each (kitchen, checkout) runs in its own process pinned to one core, the two checkouts alternating kitchen by
kitchen so that the machine's load hits both alike; it prints p50 / mean / p99 per kitchen and the ratio
this / peer. Full simulated trials with the FOV-limited simulated human (seeds 0..N-1), the paper's
defaults. ``--peer`` is a checkout of an older revision, e.g. ``git worktree add /tmp/peer main``
(its ``planner`` must offer ``make_robot(name, layout, rules, config)`` and ``run_trial``).

``--served`` keeps the garbage collector as a robot worker of the server keeps it (``server/robots/worker.py``:
``gc.freeze()`` once the robot is built and every ``FREEZE_EVERY`` decisions), so the times are those a
participant's trial gets; without it the collector runs as in any Python process.

    .venv/bin/python benchmarks/planner/latency.py --peer /tmp/peer --seeds 3 [--served]
"""

from __future__ import annotations

import argparse
import gc
import json
import os
import subprocess
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:  # the planner itself is imported in the worker, from whichever checkout it measures
    from planner.decision import Decision, Robot
    from planner.events import Event
    from planner.kb import KnowledgeBase
    from planner.state import WorldState

ROOT = Path(__file__).resolve().parents[2]


class Timed:
    """A robot whose every decision's CPU time (``time.thread_time``: what the decision costs one core, whatever
    else the machine runs) and wall time are kept."""

    def __init__(self, robot: Robot, freeze_every: int | None = None) -> None:
        """``freeze_every``: freeze the collector's objects once reset and every so many decisions (``--served``)."""
        self.robot = robot
        self.freeze_every = freeze_every
        self.cpu_ms: list[float] = []
        self.wall_ms: list[float] = []

    def reset(self, world: WorldState, kb: KnowledgeBase | None = None) -> None:
        self.robot.reset(world, kb)
        if self.freeze_every is not None:
            gc.freeze()

    def decide(self, world: WorldState, events: Sequence[Event], rng: np.random.Generator,
               deadline: float | None = None) -> Decision:
        cpu, wall = time.thread_time(), time.perf_counter()
        decision = self.robot.decide(world, events, rng, deadline)
        self.cpu_ms.append((time.thread_time() - cpu) * 1000)
        self.wall_ms.append((time.perf_counter() - wall) * 1000)
        if self.freeze_every is not None and len(self.cpu_ms) % self.freeze_every == 0:
            gc.freeze()
        return decision


def measure(kitchen: str, robot: str, seeds: int, served: bool = False) -> dict[str, list[float]]:
    """CPU and wall decision times (ms) of ``robot`` over trials with seeds 0..seeds-1 on ``kitchen``, and the
    trials' ticks (the planner of whichever checkout is first on ``sys.path``; ``served``: see the module)."""
    from planner.planner_config import PlannerConfig
    from planner.play import run_trial
    from planner.robots import make_robot
    from planner.rules import Rules
    from study_config import load_layout

    layout = load_layout(kitchen)
    cpu: list[float] = []
    wall: list[float] = []
    ticks: list[float] = []
    freeze_every: int | None = None
    if served:
        from server.robots.worker import FREEZE_EVERY

        freeze_every = FREEZE_EVERY
    for seed in range(seeds):
        timed = Timed(make_robot(robot, layout, Rules(), PlannerConfig()), freeze_every)
        ticks.append(run_trial(layout, seed, robot=timed).ticks)
        cpu.extend(timed.cpu_ms)
        wall.extend(timed.wall_ms)
    return {"cpu": cpu, "wall": wall, "ticks": ticks}


def run_in(checkout: Path, kitchen: str, robot: str, seeds: int, served: bool) -> dict[str, list[float]]:
    env = {**os.environ, "PYTHONPATH": str(checkout)}
    out = subprocess.run([sys.executable, __file__, "--worker", kitchen, "--robot", robot, "--seeds", str(seeds),
                          *(["--served"] if served else [])],
                         env=env, cwd=checkout, check=True, capture_output=True, text=True).stdout
    return {k: [float(t) for t in v] for k, v in json.loads(out).items()}


def stats(times: list[float]) -> tuple[float, float, float]:
    t = np.array(times)
    return float(np.percentile(t, 50)), float(t.mean()), float(np.percentile(t, 99))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robot", default="fov_aware")
    parser.add_argument("--seeds", type=int, default=3)
    parser.add_argument("--kitchens", default="all")
    parser.add_argument("--peer", type=Path, help="another checkout to compare with")
    parser.add_argument("--served", action="store_true",
                        help="keep the garbage collector as the server's robot workers do (see the module)")
    parser.add_argument("--worker", metavar="KITCHEN", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if hasattr(os, "sched_setaffinity"):
        os.sched_setaffinity(0, {sorted(os.sched_getaffinity(0))[0]})
    if args.worker:
        print(json.dumps(measure(args.worker, args.robot, args.seeds, args.served)))
        return 0
    from study_config import layout_names

    kitchens = layout_names() if args.kitchens == "all" else tuple(args.kitchens.split(","))
    print(f"{args.robot} decision time in ms, seeds 0..{args.seeds - 1}, one core; this = {ROOT}"
          + (f", peer = {args.peer}" if args.peer else "")
          + ("; the collector kept as the robot workers keep it" if args.served else ""))
    print("cpu: the decision's CPU time (thread_time, what it costs one core); wall: its elapsed time "
          "(includes waiting for the CPU on a busy machine)")
    head = f"{'kitchen':<10}{'cpu p50':>9}{'mean':>8}{'p99':>8}{'wall p99':>10}{'ticks':>7}"
    print(head + (f"{'peer p50':>10}{'mean':>8}{'p99':>8}{'wall p99':>10}{'ticks':>7}{'p99 ratio':>11}"
                  if args.peer else ""))
    worst = peer_worst = 0.0
    for kitchen in kitchens:
        peer = run_in(args.peer, kitchen, args.robot, args.seeds, args.served) if args.peer else None
        mine = run_in(ROOT, kitchen, args.robot, args.seeds, args.served)
        p50, mean, p99 = stats(mine["cpu"])
        worst = max(worst, p99)
        line = (f"{kitchen:<10}{p50:9.2f}{mean:8.2f}{p99:8.2f}{stats(mine['wall'])[2]:10.2f}"
                f"{np.mean(mine['ticks']):7.1f}")
        if peer is not None:
            q50, qmean, q99 = stats(peer["cpu"])
            peer_worst = max(peer_worst, q99)
            line += (f"{q50:10.2f}{qmean:8.2f}{q99:8.2f}{stats(peer['wall'])[2]:10.2f}{np.mean(peer['ticks']):7.1f}"
                     f"{p99 / q99:11.2f}")
        print(line, flush=True)
    print(f"worst cpu p99: {worst:.2f} ms" + (f" (peer {peer_worst:.2f} ms)" if args.peer else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
