"""No stall, with any partner (issue 18 part 1): unfinished trials per robot planner and partner model.

Every planner (``fov_aware``, ``baseline``, ``no_rollout``) plays the shipped kitchens and generated ones
(:mod:`planner.layout_gen`, generator seeds ``--generator-seeds``) with two partners in the human's place:

* ``simulated`` – the simulated FOV-limited human (docs/domain.md §4);
* ``adversary`` – :class:`planner.adversary.AdversarialHuman`: random subtasks including impossible ones,
  standing in the only access cell of a station, random interrupts, long still stretches, for at most
  ``--budget`` ticks (default 150), then the simulated human. The task stays possible because the
  disruption ends; a trial unfinished at the horizon (400 ticks) is a **stall** of the robot.

Printed: unfinished / trials per (partner, robot), then every stall with its kitchen, seed, robot, partner
and the last tick at which the kitchen changed (:func:`planner.adversary.last_progress_tick`), and the two
agents' final poses and held objects, so it can be replayed with ``run_trial``.

Run (from the repository root)::

    .venv/bin/python benchmarks/planner/no_stall.py --seeds 3 --generator-seeds 1000-1019 --jobs 2
"""

from __future__ import annotations

import argparse
import sys
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass

from planner.adversary import AdversarialHuman, AdversaryConfig, last_progress_tick
from planner.layout import Layout
from planner.layout_gen import generate_named
from planner.play import run_trial
from planner.planner_config import PlannerConfig
from planner.robots import make_robot
from planner.rules import Rules
from study_config import layout_names, load_layout

ROBOTS = ("fov_aware", "baseline", "no_rollout")
PARTNERS = ("simulated", "adversary")


@dataclass(frozen=True, slots=True)
class StallSpec:
    kitchen: str
    """A shipped kitchen's name, or ``gen:<seed>`` for a generated one."""
    robot: str
    partner: str
    seed: int
    budget: int = AdversaryConfig().budget


def kitchen(name: str) -> Layout:
    return generate_named(int(name[4:])) if name.startswith("gen:") else load_layout(name)


def run_one(spec: StallSpec) -> dict[str, object]:
    layout = kitchen(spec.kitchen)
    rules = Rules()
    robot = make_robot(spec.robot, layout, rules, PlannerConfig())
    human = AdversarialHuman(layout, rules, AdversaryConfig(budget=spec.budget)) if spec.partner == "adversary" else None
    result = run_trial(layout, spec.seed, robot=robot, human=human, record=True)
    final = result.final
    return {"kitchen": layout.name, "robot": spec.robot, "partner": spec.partner, "seed": spec.seed,
            "finished": result.finished, "ticks": result.ticks,
            "last_progress": last_progress_tick(layout, rules, result.actions),
            "human": (final.human.pos, final.human.facing.value, final.human.held),
            "robot_state": (final.robot.pos, final.robot.facing.value, final.robot.held)}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=3, help="simulation seeds per kitchen")
    parser.add_argument("--first-seed", type=int, default=0)
    parser.add_argument("--generator-seeds", default="1000-1019", help="generated kitchens (a range; 'none')")
    parser.add_argument("--shipped", default="all", help="all, none, or comma-separated names")
    parser.add_argument("--robots", default=",".join(ROBOTS))
    parser.add_argument("--partners", default=",".join(PARTNERS))
    parser.add_argument("--budget", type=int, default=AdversaryConfig().budget)
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args(argv)
    shipped = [] if args.shipped == "none" else list(layout_names()) if args.shipped == "all" else \
        args.shipped.split(",")
    generated = []
    if args.generator_seeds != "none":
        low, _, high = args.generator_seeds.partition("-")
        generated = [f"gen:{s}" for s in range(int(low), int(high or low) + 1)]
    robots, partners = args.robots.split(","), args.partners.split(",")
    seeds = range(args.first_seed, args.first_seed + args.seeds)
    specs = [StallSpec(k, r, p, s, args.budget) for s in seeds for p in partners
             for k in shipped + generated for r in robots]
    rows = []
    with ProcessPoolExecutor(max_workers=args.jobs) as pool:
        for i, row in enumerate(pool.map(run_one, specs, chunksize=1), 1):
            rows.append(row)
            if i % 20 == 0 or i == len(specs):
                print(f"{i}/{len(specs)} trials", file=sys.stderr, flush=True)
    print(f"{len(shipped)} shipped + {len(generated)} generated kitchens × seeds {seeds.start}–{seeds.stop - 1}; "
          f"adversary budget {args.budget} ticks; horizon {Rules().horizon}")
    print(f"{'partner':<11}{'robot':<12}{'unfinished':>11}{'trials':>8}{'mean ticks':>12}")
    for partner in partners:
        for robot in robots:
            part = [r for r in rows if r["partner"] == partner and r["robot"] == robot]
            if not part:
                continue
            stalled = sum(1 for r in part if not r["finished"])
            mean = sum(int(str(r["ticks"])) for r in part) / len(part)
            print(f"{partner:<11}{robot:<12}{stalled:>11}{len(part):>8}{mean:>12.1f}")
    stalls = [r for r in rows if not r["finished"]]
    print(f"stalls: {len(stalls)}")
    for r in stalls:
        print(f"  kitchen {r['kitchen']} seed {r['seed']} robot {r['robot']} partner {r['partner']}: "
              f"no change in the kitchen after tick {r['last_progress']}; human {r['human']}, "
              f"robot {r['robot_state']}")
    return 1 if stalls else 0


if __name__ == "__main__":
    sys.exit(main())
