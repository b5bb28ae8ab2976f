"""How little the person's KB could be wrong about the robot's hands: a lower bound on the robot gap (docs/domain.md
§6, "Behaviours").

For each robot × kitchen × seed, one simulated trial as ``behaviours.py`` plays it, cut into *legs*: the stretches
in which the robot holds one thing (or nothing), from the tick its hands change to the tick before they change
again. Knowing the person's actual poses tick by tick, the robot could have walked each leg otherwise; the
earliest tick at which a walk has stood ``kb_delay`` consecutive ticks in the person's view is when the person could
at best acknowledge the leg's hands (docs/domain.md §3). Over the legs, a small dynamic programme chooses for each
leg whether the person acknowledges it (at that earliest tick) or never does (a load the person never learned of
leaves their KB right once it is put down), keeping what the person believes the robot holds; the fewest wrong
ticks over the trial's ticks as played is the bound. Two bounds, by what the other walks must keep:

* **same work**: every interaction of the robot (each change of hands, each chop and wash) at the same tick as
  played, facing the same station; between them any walk, stays included. A robot with the team's speed doing
  the same work could not leave the person's KB wrong less often.
* **free, d**: only each leg's end kept (facing the station where its hands change, at most ``d`` ticks later than
  played); what the robot did in between (chopping, washing, waiting) may be dropped. Looser still.

Both relax the trial in the robot's favour: the person's poses are those played (a robot elsewhere could have made
them act otherwise; past the trial's end the last one holds), extra ticks delay nothing after them, and the person
never blocks a robot waiting in their way. The walks never step into the person's cell. The *lag* (``kb_delay −
1`` ticks after each change of hands, even with the robot always in view; ``behaviours.py``) is below every bound.

Printed per group (each shipped kitchen; generated kitchens together) and robot: the trials, the robot gap as
played, its lag, and the bounds (% of ticks, means over trials).

    .venv/bin/python benchmarks/planner/hands_bound.py --seeds 30
    .venv/bin/python benchmarks/planner/hands_bound.py --shipped "" --generator-seeds 1000-1019 --seeds 3
"""

from __future__ import annotations

import argparse
import statistics
import sys
from collections.abc import Sequence
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from behaviours import kitchens_of, replayed, trial_arguments

from planner.behaviours import Frame
from planner.fov import view
from planner.geometry import Action, Pos
from planner.layout import Layout
from planner.paths import UNREACHABLE, Pose, distances_to, tick_successors
from planner.perception import FOV_ANGLE, KB_DELAY
from planner.state import WorldState

DETOURS = (0, 2, 4)


def earliest_acknowledgement(layout: Layout, worlds: Sequence[WorldState], start: int,
                             anchors: Sequence[tuple[int, Pos]], angle: float = FOV_ANGLE,
                             kb_delay: int = KB_DELAY) -> int | None:
    """The fewest ticks from frame ``start`` (``worlds[i]``: the world after tick ``i + 1``; the robot as played
    there) before the person could have acknowledged the robot's hands, over the walks that stand facing each
    anchor's station the frame before it and interact there (stay) at its frame: ``anchors`` (frame, station), in
    order, the last one the interact that changes the hands again (none for the trial's last leg). The person's
    poses are those played, the last one held past the trial's end. ``None`` when no such walk stands ``kb_delay``
    consecutive ticks in view before the last anchor."""
    last_frame = len(worlds) - 1
    final = anchors[-1][0] - 1 if anchors else last_frame
    successors = tick_successors(layout)
    tables = {station: distances_to(layout, station) for _, station in anchors}

    def seen(pose: Pose, frame: int) -> bool:
        person = worlds[min(frame, last_frame)].human
        return pose[0] in view(layout, person.pos, person.facing, angle).cells

    def in_time(pose: Pose, frame: int) -> bool:
        ahead = next(((t, station) for t, station in anchors if t > frame), None)
        return ahead is None or frame + tables[ahead[1]].get(pose, UNREACHABLE) <= ahead[0] - 1

    robot = worlds[start].robot
    first: Pose = (robot.pos, robot.facing)
    if not in_time(first, start):
        return None
    fixed = dict(anchors)
    layer: dict[Pose, set[int]] = {first: {int(seen(first, start))}}
    for frame in range(start, final + 1):
        if any(s >= kb_delay for streaks in layer.values() for s in streaks):
            return frame - start
        if frame == final or not layer:
            return None
        at = frame + 1
        person = worlds[min(at, last_frame)].human.pos
        station = fixed.get(at)
        nxt: dict[Pose, set[int]] = {}
        for pose, streaks in layer.items():
            if station is not None:  # an interact: it stays, facing the station
                nexts = [pose] if tables[station].get(pose) == 0 else []
            else:
                nexts = [q for _, q in successors[pose]]
            for q in nexts:
                if (q[0] != pose[0] and q[0] == person) or not in_time(q, at):
                    continue
                now = seen(q, at)
                nxt.setdefault(q, set()).update(s + 1 if now else 0 for s in streaks)
        layer = nxt
    return None


def least_wrong(legs: Sequence[tuple[str | None, int, int | None]]) -> int:
    """The fewest ticks the person's KB is wrong about the robot's hands over ``legs`` (what the robot holds, the
    leg's ticks, the earliest acknowledgement or ``None``), the person believing empty hands at the start: per leg,
    acknowledged (if it can be) or not, whichever leaves the fewest wrong ticks over the whole trial."""
    best: dict[str | None, int] = {None: 0}  # what the person believes the robot holds → fewest wrong ticks so far
    for held, ticks, ack in legs:
        nxt: dict[str | None, int] = {}
        for belief, wrong in best.items():
            options = [(belief, wrong)] if belief == held else [(belief, wrong + ticks)]  # never acknowledged
            if belief != held and ack is not None:
                options.append((held, wrong + ack))
            for after, total in options:
                nxt[after] = min(total, nxt.get(after, total))
        best = nxt
    return min(best.values())


def legs_of(frames: Sequence[Frame]) -> list[tuple[int, int]]:
    """``(start, end)`` frames of each stretch with the same hands (empty ones included), in order."""
    spans, start = [], 0
    for t in range(1, len(frames)):
        if frames[t].held != frames[t - 1].held:
            spans.append((start, t))
            start = t
    if frames:
        spans.append((start, len(frames)))
    return spans


def run_one(job: tuple[str, str, int]) -> tuple[str, str, list[float]]:
    """Of one trial, % of ticks: the robot gap as played, its lag, and the bound per detour of :data:`DETOURS`."""
    kitchen, robot_name, seed = job
    trial = replayed(kitchen, robot_name, seed)
    layout, result, worlds, frames = trial.layout, trial.result, trial.worlds, trial.frames
    ticks = max(len(frames), 1)
    played = result.hands
    spans = legs_of(frames)
    # the robot's interacts: at frame t it stood, facing the station, where it stood at frame t - 1
    interacts = {t: worlds[t].robot.facing.ahead(worlds[t].robot.pos)
                 for t, (_, r_action) in enumerate(result.actions) if r_action is Action.INTERACT and t > 0}
    row = [100.0 * played.wrong / ticks, 100.0 * played.lag / ticks]
    same = [(frames[a].held, b - a, earliest_acknowledgement(
        layout, worlds, a, [(t, interacts[t]) for t in range(a + 1, b + 1) if t in interacts])) for a, b in spans]
    row.append(100.0 * least_wrong(same) / ticks)
    for d in DETOURS:
        free = [(frames[a].held, b - a, earliest_acknowledgement(
            layout, worlds, a, [(b + d, interacts[b])] if b in interacts else [])) for a, b in spans]
        row.append(100.0 * least_wrong(free) / ticks)
    return kitchen, robot_name, row


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    trial_arguments(parser, "baseline,fov_aware")
    args = parser.parse_args(argv)
    kitchens = kitchens_of(args)
    if not kitchens or args.seeds < 1:
        parser.error("no trials: give --shipped or --generator-seeds, and --seeds 1 or more")
    jobs = [(k, r, s) for k in kitchens for r in args.robots.split(",") for s in range(args.seeds)]
    groups: dict[tuple[str, str], list[list[float]]] = {}
    with ProcessPoolExecutor(max(args.jobs, 1)) as pool:
        for kitchen, robot, row in pool.map(run_one, jobs):
            groups.setdefault(("generated" if kitchen.startswith("gen_") else kitchen, robot), []).append(row)
    print("% of ticks the person's KB is wrong about what the robot holds (mean over trials)")
    print(f"{'kitchen':<11}{'robot':<11}{'trials':>7}{'played':>8}{'lag':>7}{'same work':>11}"
          + "".join(f"{'free d=' + str(d):>10}" for d in DETOURS))
    for (group, robot), rows in sorted(groups.items()):
        means = [statistics.mean(column) for column in zip(*rows, strict=True)]
        print(f"{group:<11}{robot:<11}{len(rows):>7}{means[0]:>8.1f}{means[1]:>7.1f}{means[2]:>11.1f}"
              + "".join(f"{m:>10.1f}" for m in means[3:]))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
