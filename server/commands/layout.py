"""``steakhouse layout check FILE_OR_NAME...``: exit 0 when every layout is valid, else 1 with one line per
problem of every invalid layout (``invalid: FILE:LINE:COLUMN: reason``).

``steakhouse layout generate --seed S [--count N] [--size WxH] [--style STYLE] --out DIR``: writes N kitchens
in the paper's style (:mod:`planner.layout_gen`), kitchen ``i`` drawn from generator seed ``S + i`` and
named ``gen_<seed>_<style>.layout``; the same arguments always write the same files.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from server.cli import UsageError


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    parser = subparsers.add_parser("layout", help="work with kitchen layouts")
    inner = parser.add_subparsers(dest="layout_command", metavar="ACTION", required=True)
    check = inner.add_parser("check", help="validate layouts (shipped names or files)")
    check.add_argument("layouts", nargs="+", metavar="FILE_OR_NAME")
    check.set_defaults(handler=_check, subparser=check)
    generate = inner.add_parser("generate", help="write random kitchens in the paper's style")
    generate.add_argument("--seed", type=int, required=True, help="generator seed of the first kitchen")
    generate.add_argument("--count", type=int, default=1, help="kitchens to write (seeds S, S+1, …)")
    generate.add_argument("--size", metavar="WxH", help="grid size with walls (default: drawn per style)")
    generate.add_argument("--style", help="island, peninsula, corridor or split (default: drawn per kitchen)")
    generate.add_argument("--out", required=True, metavar="DIR")
    generate.set_defaults(handler=_generate, subparser=generate)


def _check(args: argparse.Namespace) -> int:
    from planner.layout import LayoutError
    from study_config import load_layout

    failed = 0
    for name in args.layouts:
        try:
            layout = load_layout(name)
        except LayoutError as exc:
            for line in exc.lines():
                print(f"invalid: {line}", file=sys.stderr)
            failed += 1
        else:
            print(f"ok: {name} ({layout.width}x{layout.height})")
    return 1 if failed else 0


def _generate(args: argparse.Namespace) -> int:
    from planner.layout_gen import GenerationError, KitchenRequest, generate_named, parse_size

    if args.count < 1:
        raise UsageError("--count must be at least 1")
    if args.seed < 0:
        raise UsageError("--seed must be 0 or more")
    try:
        request = KitchenRequest(style=args.style, size=parse_size(args.size) if args.size else None)
        kitchens = [generate_named(args.seed + i, request) for i in range(args.count)]
    except GenerationError as exc:
        raise UsageError(str(exc)) from exc
    out = Path(args.out)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise UsageError(f"--out {out}: {exc.strerror}") from exc
    for layout in kitchens:
        path = out / f"{layout.name}.layout"
        path.write_text(layout.text(), encoding="utf-8")
        print(f"wrote {path} ({layout.width}x{layout.height})")
    return 0
