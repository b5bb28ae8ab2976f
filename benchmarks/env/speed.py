"""Kitchen environment throughput against the world's own step (docs/robots.md, "The environment").

Three runners take uniformly random actions from seeded generators on one kitchen and reset when their episode
ends (horizon 400): the world's own step (``planner.step.step``, nothing else: the peer), the PettingZoo
``KitchenEnv.step`` (the step plus both agents' observations, the person's masked) and the Gymnasium
``RobotEnv.step`` (the step, the simulated person's choice and KB, the robot's observation). They alternate in
rounds inside one process, so machine noise hits all three; each rate is the median over rounds. Printed: the
steps per second of each and each environment's ratio to the world's step.

    .venv/bin/python benchmarks/env/speed.py [--kitchen none_3] [--rounds 7] [--steps 4000]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from collections.abc import Callable

import numpy as np

from planner.env.kitchen import KitchenEnv
from planner.env.single import RobotEnv
from planner.geometry import ACTIONS
from planner.layout import Layout
from planner.rules import Rules
from planner.state import initial_state, is_done
from planner.step import step
from study_config import load_layout


def world_runner(layout: Layout, seed: int) -> Callable[[int], None]:
    rules, rng = Rules(), np.random.default_rng(seed)
    world = initial_state(layout, rules)

    def run(steps: int) -> None:
        nonlocal world
        for h, r in rng.integers(len(ACTIONS), size=(steps, 2)):
            world, _ = step(layout, world, {"human": ACTIONS[h], "robot": ACTIONS[r]}, rules)
            if is_done(world, rules):
                world = initial_state(layout, rules)

    return run


def kitchen_runner(layout: Layout, seed: int) -> Callable[[int], None]:
    env, rng = KitchenEnv(layout), np.random.default_rng(seed)
    env.reset(seed=seed)

    def run(steps: int) -> None:
        for h, r in rng.integers(len(ACTIONS), size=(steps, 2)):
            env.step({"human": int(h), "robot": int(r)})
            if not env.agents:
                env.reset()

    return run


def robot_runner(layout: Layout, seed: int) -> Callable[[int], None]:
    env, rng = RobotEnv(layout), np.random.default_rng(seed)
    env.reset(seed=seed)

    def run(steps: int) -> None:
        for r in rng.integers(len(ACTIONS), size=steps):
            _, _, done, cut, _ = env.step(int(r))
            if done or cut:
                env.reset()

    return run


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--kitchen", default="none_3")
    parser.add_argument("--rounds", type=int, default=7)
    parser.add_argument("--steps", type=int, default=4000)
    args = parser.parse_args(argv)
    layout = load_layout(args.kitchen)
    runners = {"world step": world_runner(layout, 0), "KitchenEnv (PettingZoo)": kitchen_runner(layout, 0),
               "RobotEnv (Gymnasium)": robot_runner(layout, 0)}
    for run in runners.values():
        run(200)  # warm the caches (views, paths)
    rates: dict[str, list[float]] = {name: [] for name in runners}
    for _ in range(args.rounds):
        for name, run in runners.items():
            start = time.perf_counter()
            run(args.steps)
            rates[name].append(args.steps / (time.perf_counter() - start))
    median = {name: statistics.median(values) for name, values in rates.items()}
    base = median["world step"]
    print(f"kitchen {layout.name} ({layout.width}x{layout.height}), {args.rounds} rounds of {args.steps} random steps")
    for name, rate in median.items():
        print(f"{name:<26}{rate:>12,.0f} steps/s   ratio to the world's step: {rate / base:.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
