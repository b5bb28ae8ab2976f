"""``steakhouse layout check FILE_OR_NAME...``: exit 0 when every layout is valid, else 1 naming each problem."""

from __future__ import annotations

import argparse
import sys


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser("layout", help="work with kitchen layouts")
    inner = parser.add_subparsers(dest="layout_command", metavar="ACTION", required=True)
    check = inner.add_parser("check", help="validate layouts (shipped names or files)")
    check.add_argument("layouts", nargs="+", metavar="FILE_OR_NAME")
    check.set_defaults(handler=_check, subparser=check)


def _check(args: argparse.Namespace) -> int:
    from planner.layout import LayoutError
    from study_config import load_layout

    failed = 0
    for name in args.layouts:
        try:
            layout = load_layout(name)
        except LayoutError as exc:
            print(f"invalid: {exc}", file=sys.stderr)
            failed += 1
        else:
            print(f"ok: {name} ({layout.width}x{layout.height})")
    return 1 if failed else 0
