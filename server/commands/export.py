"""``steakhouse export``: a stored study's tidy CSV files and data dictionary (see
:mod:`analysis.exports.study_export`).

    steakhouse export --study paper_study --out exports/paper_study [--database-url URL] [--include-invalid]
                      [--include-pilot]

Main trials the server marked invalid (robot decisions past their deadline; docs/operations.md, "Robot
health") are listed in ``excluded.csv`` with the reason and left out of ``cells.csv``; ``--include-invalid``
keeps them there. Simulated pilot participants (``steakhouse pilot``) are left out unless ``--include-pilot``.

Without ``--database-url`` the store is the one ``steakhouse serve`` uses by default (``DATABASE_URL`` /
``STEAKHOUSE_DATABASE_URL``, else ``sqlite:///./data/steakhouse.sqlite3``). The store is only read.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path
from typing import Any

from server.cli import UsageError


def register(subparsers: Any) -> None:
    """Add the ``export`` subcommand to the ``steakhouse`` parser."""
    p = subparsers.add_parser(
        "export",
        help="tidy CSV files of a stored study (ticks, trials, cells, wide, answers) and a data dictionary",
        description="Write a stored study's per-tick, per-trial, per participant × condition (ANOVA input) and "
                    "wide CSV files, questionnaire answers, participants with flags, the excluded participants "
                    "with reasons, and a data dictionary describing every column.",
        epilog="example: steakhouse export --study paper_study --out exports/paper_study",
    )
    p.add_argument("--study", metavar="ID", required=True, help="study id in the store")
    p.add_argument("--out", metavar="DIR", type=Path, required=True, help="output folder (created if needed)")
    p.add_argument("--database-url", metavar="URL",
                   help="SQLAlchemy URL of the store (default: the one steakhouse serve uses)")
    p.add_argument("--include-invalid", action="store_true",
                   help="keep main trials the server marked invalid (too many missed robot decisions) in "
                        "cells.csv; by default they are only listed in excluded.csv")
    p.add_argument("--include-pilot", action="store_true",
                   help="export simulated pilot participants too (steakhouse pilot; left out by default)")
    p.set_defaults(handler=handle, subparser=p)


def database_url(value: str | None) -> str:
    """The store URL: ``value`` normalised like the server's setting, else the server's default."""
    from pydantic import ValidationError

    from server.settings import Settings

    try:
        settings = Settings(database_url=value) if value is not None else Settings()
    except ValidationError as exc:
        problems = "; ".join(f"{'.'.join(str(p) for p in e['loc'])}: {e['msg']}" for e in exc.errors())
        raise UsageError(f"invalid settings: {problems}") from None
    return settings.database_url


def check_out(path: Path, *inside: str) -> None:
    """Refuse an ``--out`` that cannot be the output folder, before anything is read or written: ``path`` (or a
    folder above it, or the sub-folder ``inside`` a command writes to) is an existing file, or the nearest folder
    that exists cannot be written."""
    for target in (path, *(path / name for name in inside)):
        if target.exists() and not target.is_dir():
            where = "" if target == path else f" holds {target.name}, which"
            raise UsageError(f"--out {path}{where} is a file, not a folder; name a folder (it is created if needed)")
    existing = next((p for p in (path, *path.parents) if p.exists()), Path("."))
    if not existing.is_dir():
        raise UsageError(f"--out {path}: {existing} is a file, not a folder")
    if not os.access(existing, os.W_OK | os.X_OK):
        raise UsageError(f"--out {path}: cannot write in {existing} (permission denied)")


def handle(args: argparse.Namespace) -> int:
    from analysis.exports.study_export import export_study
    from analysis.source.input_errors import AnalysisInputError

    check_out(args.out)
    url = database_url(args.database_url)
    try:
        result = export_study(url, args.study, args.out, include_invalid=args.include_invalid,
                              include_pilot=args.include_pilot)
    except AnalysisInputError as exc:
        raise UsageError(str(exc)) from exc
    tables = result.dataset.tables
    print(f"study {args.study}: {len(tables['participants.csv'])} participants, {len(tables['trials.csv'])} trial "
          f"attempts, {len(tables['cells.csv'])} cells, {len(tables['excluded.csv'])} participants listed in "
          "excluded.csv")
    if result.dataset.pilots_left_out:
        print(f"note: {result.dataset.pilots_left_out} simulated pilot participant(s) of this study were left out; "
              "--include-pilot exports them", file=sys.stderr)
    print(f"wrote {len(result.files)} files to {result.out_dir}")
    return 0
