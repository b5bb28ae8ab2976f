"""Train ``mylab_learned``'s table: Q-learning over skills in the kitchen environment (docs/robots.md).

The environment is ``planner.env.single.RobotEnv``: the robot is the learner, the person the simulated FOV-limited
human. Each decision picks a skill (``mylab_robots.learned.SKILLS``) ε-greedily from the table by the state read
from the robot's observation (``features``); the skill runs until it uses its station (at most 25 ticks); the
table learns from the points delivered meanwhile (discounted per tick), shaped by a potential of the state (held
dishes and busy stations are worth something, open orders cost), which leaves the best policy unchanged. Episodes
cycle over the kitchens, each with its own seed. About a minute per 3,000 episodes on one core::

    cd examples/mylab_robots && ../../.venv/bin/python train.py --episodes 10000 --out mylab_robots/q_table.json
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
from mylab_robots.learned import SKILLS, SkillRun, State, dump_table, features, skill_action

from planner.env.single import RobotEnv
from planner.geometry import ACTIONS
from study_config import load_layout

GAMMA = 0.98
HELD_WORTH = (0.0, 1.0, 1.0, 1.0, 2.5, 4.0, 6.0)
"""Potential of what the robot holds: nothing, onion, meat, dirty plate, clean plate, plated steak, dish."""


def potential(state: State) -> float:
    held, partner, grill, board, sink, orders = state
    return HELD_WORTH[held] + 0.5 * HELD_WORTH[partner] + grill + 0.6 * board + 0.6 * sink - 8.0 * orders


def train(kitchens: list[str], episodes: int, seed: int) -> tuple[dict[State, np.ndarray], list[int]]:
    envs = [RobotEnv(load_layout(name)) for name in kitchens]
    table: dict[State, np.ndarray] = {}
    rng = np.random.default_rng(seed)
    ticks: list[int] = []
    for episode in range(episodes):
        env = envs[episode % len(envs)]
        epsilon = max(0.05, 1.0 - episode / (0.7 * episodes))
        alpha = 0.2
        observation, _ = env.reset(seed=seed * 100_000 + episode)
        state = features(observation)
        done = cut = False
        while not (done or cut):
            values = table.setdefault(state, np.zeros(len(SKILLS)))
            choice = int(rng.integers(len(SKILLS))) if rng.random() < epsilon else int(np.argmax(values))
            run, gained, k, ended = SkillRun(SKILLS[choice]), 0.0, 0, False
            while not (ended or done or cut):
                action, ended = skill_action(env.layout, env.world, run)
                observation, reward, done, cut, _ = env.step(ACTIONS.index(action))
                gained += GAMMA ** k * reward
                k += 1
            after = features(observation)
            shaped = gained + GAMMA ** k * potential(after) * (not done) - potential(state)
            future = 0.0 if done else GAMMA ** k * float(table.setdefault(after, np.zeros(len(SKILLS))).max())
            values[choice] += alpha * (shaped + future - values[choice])
            state = after
        ticks.append(env.world.tick)
    return table, ticks


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--kitchens", default="none_3,mid_2,side_2")
    parser.add_argument("--episodes", type=int, default=3000)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--out", type=Path, required=True)
    args = parser.parse_args(argv)
    kitchens = args.kitchens.split(",")
    start = time.perf_counter()
    table, ticks = train(kitchens, args.episodes, args.seed)
    seconds = time.perf_counter() - start
    last = ticks[-len(kitchens) * 50:]
    print(f"{args.episodes} episodes on {', '.join(kitchens)} in {seconds:.0f} s; {len(table)} states; mean ticks "
          f"of the last {len(last)} episodes (exploring 5 % of choices): {np.mean(last):.1f}")
    about = {"kitchens": kitchens, "episodes": args.episodes, "seed": args.seed,
             "command": "train.py " + " ".join(argv if argv is not None else sys.argv[1:])}
    args.out.write_text(dump_table(table, about) + "\n", encoding="utf-8")
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
