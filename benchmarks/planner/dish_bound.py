"""How much of a dish trip any robot could show the person: an upper bound on behaviour 2 (docs/domain.md §6).

For each robot × kitchen × seed, one simulated trial as ``behaviours.py`` plays it; for every dish trip in it, the
share of the trip the person actually saw, and the largest share any walk from the trip's start could have had,
knowing the person's actual poses tick by tick (:func:`planner.dish_walk.dish_walk` given the true future instead of
a prediction, no price), for walks at most ``d`` ticks longer than the shortest. When the trip began by taking a
ready garnish, the bound's walk may also wait before taking it (the ticks waited count against ``d``). The person's
poses are those of the trial as played: a robot on another way could have made them step otherwise, so this is a
bound on what the robot's way alone can show, not on a whole other trial. The walks never step into the person's
cell; the trip as played counts among them when it was within ``d``.

Printed per group (each shipped kitchen; generated kitchens together) and robot: trips, the mean share seen, and
the mean bound per ``d`` over the trips that have one (in brackets: how many have none, the person standing in
the way of every walk within ``d``). The FOV-aware robot's trips (``dish_detour``, 6 by default) are the ones to
compare with ``d`` = 6.

    .venv/bin/python benchmarks/planner/dish_bound.py --seeds 30
    .venv/bin/python benchmarks/planner/dish_bound.py --shipped "" --generator-seeds 0-29 --seeds 2
"""

from __future__ import annotations

import argparse
import statistics
import sys
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from behaviours import kitchens_of, replayed, trial_arguments

from planner.behaviours import Frame, holdings
from planner.dish_walk import dish_walk, walk_seen
from planner.layout import Layout
from planner.objects import DISH, STEAK_PLATE
from planner.paths import UNREACHABLE, Pose, nearest_distances
from planner.perception import FOV_ANGLE
from planner.state import WorldState

DETOURS = (0, 2, 4, 6)


def best_share(layout: Layout, worlds: list[WorldState], frames: list[Frame], start: int,
               detour: int) -> float | None:
    """The largest share of the trip that begins at frame ``start`` (the first with the dish; ``worlds[i]`` is the
    world after tick ``i + 1``, ``frames[i]`` its frame) the person could have seen, within ``detour`` extra ticks;
    ``None`` when no walk within them reaches the counter (the person stands in the way)."""
    garnish = start > 0 and worlds[start - 1].robot.held == STEAK_PLATE
    origin = start - 1 if garnish else start
    robot = worlds[origin].robot
    pose: Pose = (robot.pos, robot.facing)
    poses = [(w.human.pos, w.human.facing) for w in worlds[origin + 1:]]
    if not poses:
        return None
    seen, ticks = (0, 0) if garnish else (int(frames[origin].seen), 1)
    plan = dish_walk(layout, FOV_ANGLE, pose, [(1.0, poses)], detour, 0.0, garnish, (seen, ticks))
    if not plan:
        return None
    more_seen, more_ticks = walk_seen(layout, FOV_ANGLE, pose, plan, poses, garnish)
    return (seen + more_seen) / (ticks + more_ticks) if ticks + more_ticks else None


def bound(*shares: float | None) -> float | None:
    known = [s for s in shares if s is not None]
    return max(known) if known else None


def run_one(job: tuple[str, str, int]) -> tuple[str, str, list[list[float | None]]]:
    """Per dish trip of one trial (as :func:`planner.behaviours.measure` counts them): the share seen, then the
    bound per detour of :data:`DETOURS` (``None``: no walk within that detour, neither the trip as played)."""
    kitchen, robot_name, seed = job
    trial = replayed(kitchen, robot_name, seed)
    layout, worlds, frames = trial.layout, trial.worlds, trial.frames
    to_serve = nearest_distances(layout, layout.serves)
    trips: list[list[float | None]] = []
    for a, b in holdings(frames):
        if frames[a].held != DISH or b >= len(frames) or not frames[b].delivered:
            continue
        robot = worlds[a].robot
        extra = b - a - 1 - to_serve.get((robot.pos, robot.facing), UNREACHABLE)
        share = sum(f.seen for f in frames[a:b]) / (b - a)  # the trip as played is one walk within its extra ticks
        bounds: list[float | None] = [bound(best_share(layout, worlds, frames, a, d), share if extra <= d else None)
                                      for d in DETOURS]
        trips.append([share, *bounds])
    return kitchen, robot_name, trips


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    trial_arguments(parser, "baseline,fov_aware")
    args = parser.parse_args(argv)
    kitchens = kitchens_of(args)
    if not kitchens:
        parser.error("no kitchens: give --shipped or --generator-seeds")
    jobs = [(k, r, s) for k in kitchens for r in args.robots.split(",") for s in range(args.seeds)]
    groups: dict[tuple[str, str], list[list[float | None]]] = {}
    with ProcessPoolExecutor(max(args.jobs, 1)) as pool:
        for kitchen, robot, trips in pool.map(run_one, jobs):
            group = "generated" if kitchen.startswith("gen_") else kitchen
            groups.setdefault((group, robot), []).extend(trips)
    print(f"{'kitchen':<11}{'robot':<11}{'trips':>6}{'seen':>7}"
          + "".join(f"{'bound d=' + str(d):>11}" for d in DETOURS))
    for (group, robot), trips in sorted(groups.items()):
        if not trips:
            continue
        columns = [[v for v in c if v is not None] for c in zip(*trips, strict=True)]
        print(f"{group:<11}{robot:<11}{len(trips):>6}{statistics.mean(columns[0]):>7.2f}"
              + "".join(f"{statistics.mean(c):>7.2f} ({len(trips) - len(c)})" if c else f"{'-':>11}"
                        for c in columns[1:]))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
