"""``steakhouse simulate``: the paper's simulation experiment, in parallel worker processes."""

from __future__ import annotations

import argparse
import csv
import sys
from collections.abc import Iterable
from pathlib import Path
from typing import TYPE_CHECKING

from planner.perception import FOV_ANGLE, KB_DELAY
from server.cli import UsageError

if TYPE_CHECKING:
    from planner.experiment import TrialSpec


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    parser = subparsers.add_parser("simulate", help="robots × kitchens × seeds with the simulated human")
    parser.add_argument("--study", metavar="FILE",
                        help="a study file: its kitchens, robots (its own robot_variants too), field of view, KB "
                             "delay and world numbers (then leave out --layouts, --robots and --kb-delay)")
    parser.add_argument("--layouts", help="all (default), or comma-separated names/files")
    parser.add_argument("--robots", help="comma-separated installed robots, shipped or plug-ins (`steakhouse robots`; "
                                         "default fov_aware,baseline)")
    parser.add_argument("--seeds", type=int, default=10, help="seeds 0..N-1 per kitchen and robot")
    parser.add_argument("--human-angle", type=float, metavar="DEG",
                        help=f"the simulated person's field of view (default {FOV_ANGLE:g}, or the study's)")
    parser.add_argument("--kb-delay", type=int, help=f"the person's KB delay (default {KB_DELAY})")
    parser.add_argument("--jobs", type=int, default=0, help="worker processes (0 = one per core)")
    parser.add_argument("--out", required=True, metavar="DIR")
    parser.add_argument("--quiet", action="store_true", help="no progress bar")
    parser.set_defaults(handler=_simulate, subparser=parser)


def _simulate(args: argparse.Namespace) -> int:
    import os
    from concurrent.futures import ProcessPoolExecutor

    from analysis.pipeline.simulation import robot_effects
    from planner.experiment import COLUMNS, flagged_lines, run_spec, summarize_trials

    if args.seeds < 1:
        raise UsageError("--seeds must be at least 1")
    robots, specs = _study_specs(args) if args.study is not None else _named_specs(args)
    jobs = args.jobs or os.cpu_count() or 1
    rows: list[dict[str, object]] = []
    show = not args.quiet and sys.stderr.isatty()
    if jobs == 1:
        results = map(run_spec, specs)
        rows = _collect(results, len(specs), show)
    else:
        with ProcessPoolExecutor(max_workers=jobs) as pool:
            rows = _collect(pool.map(run_spec, specs, chunksize=1), len(specs), show)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    with (out / "trials.csv").open("w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=COLUMNS)
        writer.writeheader()
        writer.writerows(rows)
    print(summarize_trials(rows))
    for measure in ("kb_diff_freq", "kb_diff_mean", "kb_gap_mean"):  # the paper's KB gap first, ours last
        for line in robot_effects(rows, measure, robots):
            print(line)
    print(f"wrote {out / 'trials.csv'} ({len(rows)} trials)")
    return 1 if flagged_lines(rows) else 0


def _check_person(angle: float, delay: int) -> None:
    if not 0 < angle <= 360 or delay < 0:
        raise UsageError("--human-angle must be in (0, 360] and --kb-delay 0 or more")


def _named_specs(args: argparse.Namespace) -> tuple[list[str], list[TrialSpec]]:
    """The robots and trials named on the command line: planners, kitchens, the person's view and KB delay."""
    from planner import robot_catalog
    from planner.experiment import TrialSpec
    from planner.layout import LayoutError
    from study_config import layout_names, load_layout

    robots = [r.strip() for r in (args.robots or "fov_aware,baseline").split(",") if r.strip()]
    if not robots:
        raise UsageError(f"no robot named; choose from: {', '.join(robot_catalog.usable_names())}")
    for robot in robots:
        try:
            robot_catalog.entry(robot)
        except robot_catalog.RobotUnavailable as exc:
            raise UsageError(str(exc)) from exc
    layouts_arg = args.layouts or "all"
    names = list(layout_names()) if layouts_arg == "all" else [n.strip() for n in layouts_arg.split(",")]
    layouts = []
    for name in names:
        try:
            layouts.append(load_layout(name))
        except LayoutError as exc:
            raise UsageError(str(exc)) from exc
    angle = FOV_ANGLE if args.human_angle is None else args.human_angle
    delay = KB_DELAY if args.kb_delay is None else args.kb_delay
    _check_person(angle, delay)
    return robots, [TrialSpec(lay, r, s, angle, delay) for lay in layouts
                    for r in robots for s in range(args.seeds)]


def _study_specs(args: argparse.Namespace) -> tuple[list[str], list[TrialSpec]]:
    """The robots and trials of ``--study``: its kitchens and robots (a variant is played by its planner with its
    settings), the person at its field of view and KB delay, the kitchens' numbers from its world."""
    from planner.experiment import TrialSpec
    from planner.layout import LayoutError
    from study_config.catalog import load_one
    from study_config.study import StudyConfigError

    given = [flag for flag, value in (("--layouts", args.layouts), ("--robots", args.robots),
                                      ("--kb-delay", args.kb_delay)) if value is not None]
    if given:
        raise UsageError(f"--study gives the kitchens, robots and KB delay; leave out {', '.join(given)}")
    try:
        loaded = load_one(Path(args.study))
    except (StudyConfigError, LayoutError, OSError) as exc:
        raise UsageError(str(exc)) from exc
    study = loaded.study
    angles = study.fov_angle_levels
    if args.human_angle is None and len(angles) > 1:
        raise UsageError(f"the study has {len(angles)} fields of view ({', '.join(f'{a:g}' for a in angles)}): "
                         "choose one with --human-angle")
    angle = angles[0] if args.human_angle is None else args.human_angle
    _check_person(angle, study.world.kb_delay)
    robots = list(study.robots)
    settings = {name: tuple(variant.settings.items()) for name, variant in study.robot_variants.items()}
    specs = [TrialSpec(loaded.layout(kitchen.name), robot, seed, angle, study.world.kb_delay,
                       planner=loaded.planner(robot), settings=settings.get(robot, ()),
                       rules=loaded.rules)
             for kitchen in study.kitchens for robot in robots for seed in range(args.seeds)]
    return robots, specs


def _collect(results: Iterable[dict[str, object]], total: int, show: bool) -> list[dict[str, object]]:
    rows = []
    for i, row in enumerate(results, 1):
        rows.append(row)
        if show:
            filled = int(30 * i / total)
            print(f"\r[{'#' * filled}{'.' * (30 - filled)}] {i}/{total} trials", end="", file=sys.stderr, flush=True)
        elif i == total or i % max(total // 10, 1) == 0:
            print(f"{i}/{total} trials", file=sys.stderr, flush=True)
    if show:
        print(file=sys.stderr)
    return rows
