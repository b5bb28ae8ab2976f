"""World step throughput: ours (with the human's FOV and KB updated every tick) against overcooked-ai.

Both worlds take uniformly random joint actions from a seeded generator and reset when their episode
ends (horizon 400). Ours runs on ``none_3`` (15×10, the paper's ∩ kitchen); overcooked-ai 1.1.0's
``OvercookedEnv.step`` (no FOV) on its ``cramped_room``. The two alternate in rounds inside one process so
machine noise hits both; each rate is the median over rounds. The last line is ``ratio: X.XX`` (ours /
theirs). Run it through ``benchmarks/world_speed/run.sh``, which builds the peer's own environment.
"""

from __future__ import annotations

import argparse
import random
import statistics
import sys
import time
from collections.abc import Callable


def ours_runner(layout_name: str, seed: int) -> Callable[[int], None]:
    import numpy as np

    from planner.fov import view
    from planner.geometry import ACTIONS
    from planner.kb import initial_kb, update_kb
    from planner.perception import FOV_ANGLE, KB_DELAY
    from planner.rules import Rules
    from planner.state import initial_state, is_done
    from planner.step import step
    from planner.summary import kb_gap_components
    from study_config import load_layout

    layout = load_layout(layout_name)
    rules = Rules()
    rng = np.random.default_rng(seed)
    world = initial_state(layout, rules)
    kb = initial_kb(world)

    def run(steps: int) -> None:
        nonlocal world, kb  # each run goes on from where the last one left the world and the KB
        picks = rng.integers(len(ACTIONS), size=(steps, 2))
        for h, r in picks:
            world, events = step(layout, world, {"human": ACTIONS[h], "robot": ACTIONS[r]}, rules)
            kb = update_kb(kb, layout, world, angle=FOV_ANGLE, kb_delay=KB_DELAY,
                           own_events=[e for e in events if e.agent == "human"])
            kb_gap_components(kb, world, rules)
            view(layout, world.human.pos, world.human.facing, FOV_ANGLE)
            if is_done(world, rules):
                world = initial_state(layout, rules)
                kb = initial_kb(world)

    return run


def theirs_runner(seed: int) -> Callable[[int], None]:
    from overcooked_ai_py.mdp.actions import Action
    from overcooked_ai_py.mdp.overcooked_env import OvercookedEnv
    from overcooked_ai_py.mdp.overcooked_mdp import OvercookedGridworld

    mdp = OvercookedGridworld.from_layout_name("cramped_room")
    env = OvercookedEnv.from_mdp(mdp, horizon=400)
    env.reset()
    rng = random.Random(seed)
    actions = Action.ALL_ACTIONS

    def run(steps: int) -> None:
        for _ in range(steps):
            _, _, done, _ = env.step((rng.choice(actions), rng.choice(actions)))
            if done:
                env.reset()

    return run


def rate(run: Callable[[int], None], steps: int) -> float:
    start = time.perf_counter()
    run(steps)
    return steps / (time.perf_counter() - start)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=20000, help="steps per round for each world")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--layout", default="none_3")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    ours = ours_runner(args.layout, args.seed)
    try:
        theirs = theirs_runner(args.seed)
    except ImportError as exc:
        print(f"overcooked-ai is not importable here ({exc}); run benchmarks/world_speed/run.sh",
              file=sys.stderr)
        return 2
    ours(1000)
    theirs(1000)
    our_rates, their_rates = [], []
    for i in range(args.rounds):
        our_rates.append(rate(ours, args.steps))
        their_rates.append(rate(theirs, args.steps))
        print(f"round {i + 1}: ours {our_rates[-1]:,.0f} steps/s, overcooked-ai {their_rates[-1]:,.0f} steps/s")
    ours_med, theirs_med = statistics.median(our_rates), statistics.median(their_rates)
    print(f"ours ({args.layout}, FOV 120 + KB delay 3 every tick): {ours_med:,.0f} steps/s (median of {args.rounds})")
    print(f"overcooked-ai 1.1.0 OvercookedEnv.step (cramped_room, no FOV): {theirs_med:,.0f} steps/s")
    print(f"ratio: {ours_med / theirs_med:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
