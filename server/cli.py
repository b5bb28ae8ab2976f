"""The ``steakhouse`` command line.

Each subcommand lives in its own module under ``server.commands`` and exposes
``register(subparsers)``; heavy imports happen inside the handlers so that
``steakhouse layout check`` does not pay for FastAPI or pandas.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Sequence

COMMAND_MODULES = (
    "server.commands.layout",
    "server.commands.fov",
    "server.commands.play",
    "server.commands.simulate",
    "server.commands.robots",
    "server.commands.study",
    "server.commands.serve",
    "server.commands.export",
    "server.commands.analyze",
    "server.commands.pilot",
    "server.commands.power",
)


class UsageError(Exception):
    """A command-line argument that parses but makes no sense; reported with the usage line."""


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="steakhouse",
        description="Steakhouse Study: FOV-aware human-robot collaboration studies.",
    )
    subparsers = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    for name in COMMAND_MODULES:
        try:
            module = importlib.import_module(name)
        except ModuleNotFoundError as exc:
            if exc.name == name:
                continue
            raise
        module.register(subparsers)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.handler(args) or 0)
    except UsageError as exc:
        sub = getattr(args, "subparser", parser)
        sub.print_usage(sys.stderr)
        print(f"{sub.prog}: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
