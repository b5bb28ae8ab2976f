"""No stall, with any partner (docs/domain.md §5, "Joint cycles"): unfinished trials, extra steaks and joint cycles
broken per robot planner and partner model.

Every planner (``fov_aware``, ``baseline``, ``no_rollout``) plays the shipped kitchens and generated ones
(:mod:`planner.layout_gen`, generator seeds ``--generator-seeds``) with three partners in the human's place:

* ``simulated`` – the simulated FOV-limited human (docs/domain.md §4);
* ``adversary`` – :class:`planner.adversary.AdversarialHuman`: random subtasks including impossible ones,
  standing in the only access cell of a station, random interrupts, long still stretches, for at most
  ``--budget`` ticks (default 150), then the simulated human. The task stays possible because the
  disruption ends; a trial unfinished at the horizon (400 ticks) is a **stall** of the robot;
* ``still``     – :class:`planner.partner.StillHuman`: a participant who never moves from the start cell (the
  robot has to work alone). A trial one agent cannot finish with the person standing there (some kind of
  station is reached only through the person's cell: :func:`planner.alone.solo_possible`) is counted as
  **impossible**, not as unfinished.

Printed: per (partner, robot) unfinished / trials, mean ticks, **extra steaks** (steaks the robot put on a
grill while the steaks in play — meat on grills, plated steaks, dishes — already matched the orders left,
summed over the trials), **max excess** (the largest excess of steaks in play over the orders left in any
trial, whoever started them) and **cycles broken** (:mod:`planner.cycle`, summed over the trials); then every
stall with its kitchen, seed, robot, partner
and the last tick at which the kitchen changed (:func:`planner.adversary.last_progress_tick`), and the two
agents' final poses and held objects, so it can be replayed with ``run_trial``.

``--robots`` takes any installed robot, plug-ins too (``steakhouse robots``); each plays guarded
(:class:`planner.robot_guard.GuardedRobot`): a trial whose robot failed is listed and the run exits 1.

Run (from the repository root)::

    .venv/bin/python benchmarks/planner/no_stall.py --seeds 3 --generator-seeds 1000-1019 --jobs 2
"""

from __future__ import annotations

import argparse
import sys
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass

from planner import robot_catalog
from planner.adversary import AdversaryConfig, last_progress_tick
from planner.alone import solo_possible
from planner.events import EventKind
from planner.experiment import flagged_lines
from planner.geometry import Action
from planner.layout import Layout
from planner.layout_gen import generate_named
from planner.objects import DISH, STEAK_PLATE
from planner.partner import PARTNERS, partner_model
from planner.play import run_trial
from planner.robot_guard import GuardedRobot
from planner.rules import Rules
from planner.state import WorldState, initial_state
from planner.step import step
from study_config import layout_names, load_layout

ROBOTS = ("fov_aware", "fov_aware_showing", "baseline", "no_rollout")


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


def steaks_in_play(world: WorldState) -> int:
    """Meat on grills, plated steaks and dishes, held or on counters."""
    held = (world.human.held, world.robot.held, *(obj for _, obj in world.objects))
    return sum(g is not None for g in world.grills) + sum(obj in (STEAK_PLATE, DISH) for obj in held)


def extra_steaks(layout: Layout, rules: Rules, actions: tuple[tuple[Action, Action], ...]) -> tuple[int, int]:
    """Replaying a recorded trial's ``(human, robot)`` actions: the steaks the robot put on a grill beyond what
    the orders left needed (the steaks in play after it exceeded the orders left), and the largest excess of
    steaks in play over the orders left at any tick, whoever started them (0: never more than needed)."""
    world = initial_state(layout, rules)
    by_robot = excess = 0
    for human, robot in actions:
        world, events = step(layout, world, {"human": human, "robot": robot}, rules)
        over = steaks_in_play(world) - world.orders_left
        by_robot += over > 0 and any(e.agent == "robot" and e.kind is EventKind.START_COOKING for e in events)
        excess = max(excess, over)
    return by_robot, excess


def run_one(spec: StallSpec) -> dict[str, object]:
    layout = kitchen(spec.kitchen)
    rules = Rules()
    robot = GuardedRobot(robot_catalog.build(spec.robot, layout, rules))
    human = partner_model(spec.partner, layout, rules, AdversaryConfig(budget=spec.budget))
    result = run_trial(layout, spec.seed, robot=robot, human=human, record=True)
    final = result.final
    by_robot, excess = extra_steaks(layout, rules, result.actions)
    possible = spec.partner != "still" or solo_possible(layout, initial_state(layout, rules))
    return {"kitchen": layout.name, "robot": spec.robot, "partner": spec.partner, "seed": spec.seed,
            "possible": possible, "finished": result.finished, "ticks": result.ticks, "cycles": result.cycles_broken,
            "extra_steaks": by_robot, "excess": excess,
            "last_progress": last_progress_tick(layout, rules, result.actions),
            "robot_faults": robot.faults, "robot_fault": robot.first_fault or "",
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
    for robot in robots:
        try:
            robot_catalog.entry(robot)
        except robot_catalog.RobotUnavailable as exc:
            parser.error(str(exc))
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
    print(f"{'partner':<11}{'robot':<19}{'unfinished':>11}{'impossible':>11}{'trials':>8}{'mean ticks':>12}"
          f"{'extra steaks':>14}{'max excess':>12}{'cycles broken':>15}")
    for partner in partners:
        for robot in robots:
            part = [r for r in rows if r["partner"] == partner and r["robot"] == robot]
            if not part:
                continue
            stalled = sum(1 for r in part if not r["finished"] and r["possible"])
            impossible = sum(1 for r in part if not r["possible"])
            mean = sum(int(str(r["ticks"])) for r in part) / len(part)
            extra = sum(int(str(r["extra_steaks"])) for r in part)
            excess = max(int(str(r["excess"])) for r in part)
            cycles = sum(int(str(r["cycles"])) for r in part)
            print(f"{partner:<11}{robot:<19}{stalled:>11}{impossible:>11}{len(part):>8}{mean:>12.1f}{extra:>14}"
                  f"{excess:>12}{cycles:>15}")
    stalls = [r for r in rows if not r["finished"] and r["possible"]]
    print(f"stalls: {len(stalls)}")
    for r in stalls:
        print(f"  kitchen {r['kitchen']} seed {r['seed']} robot {r['robot']} partner {r['partner']}: "
              f"no change in the kitchen after tick {r['last_progress']}; human {r['human']}, "
              f"robot {r['robot_state']}")
    flagged = flagged_lines([{**r, "layout": r["kitchen"]} for r in rows])
    print("\n".join(flagged))
    return 1 if stalls or flagged else 0


if __name__ == "__main__":
    sys.exit(main())
