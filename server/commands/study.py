"""``steakhouse study validate FILE...``: check study files before anything starts.

Prints one summary line per valid file and every problem of the invalid ones (``FILE: field: reason``);
exits 0 when all files are valid, 1 otherwise. Warnings (``FILE: field: warning: reason``, on stderr) do not
make a file invalid.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any


def register(subparsers: Any) -> None:
    """Add ``study`` and its subcommands to the ``steakhouse`` parser."""
    study = subparsers.add_parser("study", help="work with study definitions (YAML)")
    commands = study.add_subparsers(dest="study_command", metavar="SUBCOMMAND", required=True)
    validate = commands.add_parser(
        "validate",
        help="check study files and list every problem",
        description="Check study files; print a summary of each valid one and every problem of the others.",
    )
    validate.add_argument("files", nargs="+", metavar="FILE", help="study YAML file")
    validate.set_defaults(handler=validate_files, subparser=validate)


def validate_files(args: argparse.Namespace) -> int:
    """Validate each file in ``args.files``; 0 when all are valid, 1 otherwise."""
    from study_config.study import StudyConfigError, load_study
    from study_config.study.fov_angles import angle_level
    from study_config.study.warnings import study_warnings

    invalid = 0
    for file in args.files:
        try:
            study = load_study(file)
        except StudyConfigError as exc:
            invalid += 1
            for problem in exc.problems:
                print(problem, file=sys.stderr)
            continue
        scheme = study.counterbalancing.scheme
        conditions = ", ".join(c.id for c in study.conditions)
        orders = len(study.condition_orders())
        print(
            f"{file}: ok: {study.id}: {len(study.conditions)} conditions ({conditions}); "
            f"{orders} condition order{'s' if orders != 1 else ''} ({scheme}"
            + (f", in {len(set(study.order_groups()))} groups of {' × '.join(study.between)} between participants"
               if study.between else "") + "); "
            f"view {' / '.join(study.view_levels)}; "
            f"field of view {' / '.join(f'{angle_level(a)}°' for a in study.fov_angle_levels)}; "
            f"config {study.config_hash()[:12]}"
        )
        for warning in study_warnings(study):
            print(f"{file}: {warning}", file=sys.stderr)
    if invalid:
        print(f"{invalid} of {len(args.files)} study file(s) invalid", file=sys.stderr)
    return 1 if invalid else 0
