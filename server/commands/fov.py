"""``steakhouse fov``: print a kitchen with the cells out of an agent's view masked."""

from __future__ import annotations

import argparse
import json

from planner.perception import FOV_ANGLE
from server.cli import UsageError

MASK = "#"


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    parser = subparsers.add_parser("fov", help="show which cells an agent sees")
    parser.add_argument("--layout", required=True, metavar="NAME_OR_FILE")
    parser.add_argument("--x", type=int, required=True)
    parser.add_argument("--y", type=int, required=True)
    parser.add_argument("--facing", required=True, choices=["north", "south", "east", "west"])
    parser.add_argument("--angle", type=float, default=FOV_ANGLE, metavar="DEG")
    parser.add_argument("--json", action="store_true", help='print {"visible": [[x, y], ...]}')
    parser.set_defaults(handler=_fov, subparser=parser)


def _fov(args: argparse.Namespace) -> int:
    from planner.fov import visible_cells
    from planner.geometry import Direction
    from planner.layout import LayoutError
    from study_config import load_layout

    if not 0 < args.angle <= 360:
        raise UsageError(f"--angle must be in (0, 360], got {args.angle:g}")
    try:
        layout = load_layout(args.layout)
    except LayoutError as exc:
        raise UsageError(str(exc)) from exc
    if (args.x, args.y) not in layout.floor:
        raise UsageError(f"({args.x}, {args.y}) is not a floor cell of {layout.name}")
    seen = visible_cells(layout, (args.x, args.y), Direction(args.facing), args.angle)
    if args.json:
        print(json.dumps({"visible": [list(c) for c in sorted(seen, key=lambda c: (c[1], c[0]))]}))
        return 0
    arrow = {"north": "^", "south": "v", "east": ">", "west": "<"}[args.facing]
    for y, row in enumerate(layout.rows):
        line = []
        for x, ch in enumerate(row):
            if (x, y) == (args.x, args.y):
                line.append(arrow)
            else:
                line.append(ch if (x, y) in seen else MASK)
        print("".join(line).replace(" ", "."))
    print(f"{len(seen)} of {layout.width * layout.height} cells in view ({MASK} = out of view, . = floor)")
    return 0
