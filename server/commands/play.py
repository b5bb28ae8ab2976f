"""``steakhouse play``: the simulated human and a simulated partner play one trial to the end."""

from __future__ import annotations

import argparse
import json

from planner.perception import FOV_ANGLE, KB_DELAY
from server.cli import UsageError


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    parser = subparsers.add_parser(
        "play", help="play one headless trial: the simulated human with a simulated partner")
    parser.add_argument("--layout", required=True, metavar="NAME_OR_FILE")
    parser.add_argument("--seed", type=int, required=True)
    parser.add_argument("--kb-delay", type=int, default=KB_DELAY, metavar="D")
    parser.add_argument("--angle", type=float, default=FOV_ANGLE, metavar="DEG", help="the human's FOV")
    parser.add_argument("--json", action="store_true")
    parser.set_defaults(handler=_play, subparser=parser)


def _play(args: argparse.Namespace) -> int:
    from planner.layout import LayoutError
    from planner.play import TrialSettings, run_trial
    from study_config import load_layout

    if not 0 < args.angle <= 360:
        raise UsageError(f"--angle must be in (0, 360], got {args.angle:g}")
    if args.kb_delay < 0:
        raise UsageError(f"--kb-delay must be 0 or more, got {args.kb_delay}")
    try:
        layout = load_layout(args.layout)
    except LayoutError as exc:
        raise UsageError(str(exc)) from exc
    result = run_trial(layout, args.seed, TrialSettings(angle=args.angle, kb_delay=args.kb_delay))
    if args.json:
        print(json.dumps(result.to_dict()))
        return 0
    print(f"layout {layout.name}, seed {args.seed}: {result.ticks} ticks, "
          f"{result.delivered} orders delivered ({'finished' if result.finished else 'horizon reached'}), "
          f"score {result.score}")
    print(f"mean KB gap {result.kb_gap_mean:.3f} per tick, {result.kb_gap_ticks_pct:.1f}% of ticks with a gap; "
          f"robot in the human's view {result.robot_in_fov_pct:.1f}% of ticks")
    return 0
