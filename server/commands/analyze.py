"""``steakhouse analyze``: two-way repeated-measures analysis of a long CSV (later: a stored study).

    steakhouse analyze --csv cells.csv --dv ticks,interrupts --within robot,kitchen \\
        --subject participant --out results/

The CSV has one row per subject and within cell. The first within factor is the one whose simple
main effects are tested within each level of the second (robot within kitchen). Output files are
listed in ``analysis.run``.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from server.cli import UsageError

STUDY_NOT_READY = "analysis of a stored study needs the store, not built yet"


def register(subparsers: Any) -> None:
    """Add the ``analyze`` subcommand to the ``steakhouse`` parser."""
    p = subparsers.add_parser(
        "analyze",
        help="two-way repeated-measures ANOVA, descriptives, plots and report",
        description=(
            "Two-way repeated-measures ANOVA of each --dv on the two --within factors, simple "
            "main effects of the first factor within each level of the second (Holm-adjusted), "
            "descriptives with within-subject 95 % CIs, plots, and a Markdown/HTML report. "
            "The CSV has one row per subject and within cell."
        ),
        epilog="example: steakhouse analyze --csv cells.csv --dv ticks,interrupts "
        "--within robot,kitchen --subject participant --out results/",
    )
    source = p.add_mutually_exclusive_group(required=True)
    source.add_argument("--csv", metavar="FILE", type=Path, help="long table, one row per cell")
    source.add_argument("--study", metavar="ID", help="analyse a study from the store")
    p.add_argument("--dv", metavar="COL[,COL...]", help="dependent variable column(s)")
    p.add_argument("--within", metavar="A,B", help="the two within factors, e.g. robot,kitchen")
    p.add_argument("--subject", metavar="COL", help="subject (participant) id column")
    p.add_argument("--out", metavar="DIR", type=Path, help="output folder (created if needed)")
    p.set_defaults(handler=handle, subparser=p)


def handle(args: argparse.Namespace) -> int:
    """Run the analysis; usage problems raise ``UsageError`` (exit code 2)."""
    if args.study is not None:
        print(f"steakhouse analyze: error: {STUDY_NOT_READY}", file=sys.stderr)
        return 2
    missing = [flag for flag in ("dv", "within", "subject", "out") if getattr(args, flag) is None]
    if missing:
        raise UsageError(f"--csv needs {', '.join('--' + m for m in missing)}")
    measures = _names(args.dv, "--dv")
    within = _names(args.within, "--within")
    if len(within) != 2:
        raise UsageError(f"--within needs exactly two factors (A,B), got {args.within!r}")
    df = _read_csv(args.csv)

    from analysis.errors import AnalysisInputError
    from analysis.run import analyze_long

    try:
        result = analyze_long(df, measures, within, args.subject, args.out)
    except AnalysisInputError as exc:
        raise UsageError(f"{args.csv}: {exc}") from exc
    for m in result.measures:
        print(f"{m.measure}: n = {m.n_used} of {m.n_total} subjects, {len(m.excluded)} excluded")
    print(f"wrote {len(result.files)} files to {result.out_dir}")
    return 0


def _names(value: str, flag: str) -> list[str]:
    names = [name.strip() for name in value.split(",")]
    if not all(names):
        raise UsageError(f"{flag} {value!r} has an empty column name")
    return names


def _read_csv(path: Path) -> Any:
    import pandas as pd

    if not path.is_file():
        raise UsageError(f"--csv {path}: no such file")
    try:
        return pd.read_csv(path)
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as exc:
        raise UsageError(f"--csv {path}: not a readable CSV table ({exc})") from exc
