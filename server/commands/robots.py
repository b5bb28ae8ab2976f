"""``steakhouse robots``: every installed robot (shipped and plug-ins) with its package and version.

    steakhouse robots                 one line per robot: name, package, version, where it comes from, and why it
                                      cannot be used when it cannot (exit 1 when any cannot)
    steakhouse robots --settings NAME the settings a study's robot_variants may give robot NAME: name, type, default
"""

from __future__ import annotations

import argparse
import dataclasses
import typing
from typing import Any

from server.cli import UsageError


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser(
        "robots", help="list the installed robots (shipped and plug-ins) with their package and version",
        description="List every robot a study may name: the shipped planners and the plug-ins installed packages "
                    "register under the entry-point group steakhouse.robots (docs/robots.md).")
    parser.add_argument("--settings", metavar="NAME", help="list the settings of robot NAME instead")
    parser.set_defaults(handler=handle, subparser=parser)


def handle(args: argparse.Namespace) -> int:
    from planner import robot_catalog
    from study_config.study.robots import STUDY_SET

    if args.settings is not None:
        try:
            entry = robot_catalog.entry(args.settings)
        except robot_catalog.RobotUnavailable as exc:
            raise UsageError(str(exc)) from exc
        declared = entry.usable().settings
        hints = typing.get_type_hints(declared)
        print(f"{entry.name} ({entry.package} {entry.version}): settings of {declared.__module__}."
              f"{declared.__qualname__}")
        for field in dataclasses.fields(declared):
            if field.name in STUDY_SET:
                continue  # the person the study shows, never a setting of a variant
            kind = hints[field.name]
            default = field.default if field.default is not dataclasses.MISSING else "(computed)"
            shown = kind.__name__ if isinstance(kind, type) else str(kind).replace("typing.", "")
            print(f"  {field.name}: {shown} = {default!r}")
        return 0
    entries = robot_catalog.installed()
    width = max(len(e.name) for e in entries)
    broken = 0
    for entry in entries:
        status = "ok" if entry.problem is None else f"cannot be used: {entry.problem}"
        summary = entry.plugin.summary if entry.plugin is not None and entry.problem is None else ""
        broken += entry.problem is not None
        print(f"{entry.name:<{width}}  {entry.package} {entry.version}  {entry.source}  {status}"
              + (f"  ({summary})" if summary else ""))
    return 1 if broken else 0
