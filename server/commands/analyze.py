"""``steakhouse analyze``: two-way repeated-measures analysis of a long CSV or of a stored study.

    steakhouse analyze --csv cells.csv --dv ticks,interrupts --within robot,kitchen \\
        --subject participant --out results/
    steakhouse analyze --study paper_study --out results/ [--dv kb_gap_mean,ticks] [--database-url URL]

The CSV has one row per subject and within cell. The first within factor is the one whose simple
main effects are tested within each level of the second (robot within kitchen). Output files are
listed in ``analysis.run``. A stored study is first exported to ``<out>/data/`` (``analysis.export``);
its ``cells.csv`` is analysed with ``within = robot, kitchen`` and ``subject = participant`` (default
measures: ``analysis.study.DEFAULT_MEASURES``).
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from server.cli import UsageError


def register(subparsers: Any) -> None:
    """Add the ``analyze`` subcommand to the ``steakhouse`` parser."""
    p = subparsers.add_parser(
        "analyze",
        help="two-way repeated-measures ANOVA, descriptives, plots and report",
        description=(
            "Two-way repeated-measures ANOVA of each --dv on the two --within factors, simple "
            "main effects of the first factor within each level of the second (Holm-adjusted), "
            "descriptives with within-subject 95 % CIs, plots, and a Markdown/HTML report. "
            "The CSV has one row per subject and within cell. With --study the stored study is "
            "exported to OUT/data/ first and its cells.csv analysed (robot × kitchen, subject "
            "participant; participants left out are listed with reasons in the report)."
        ),
        epilog="examples: steakhouse analyze --csv cells.csv --dv ticks,interrupts "
        "--within robot,kitchen --subject participant --out results/ | "
        "steakhouse analyze --study paper_study --out results/",
    )
    source = p.add_mutually_exclusive_group(required=True)
    source.add_argument("--csv", metavar="FILE", type=Path, help="long table, one row per cell")
    source.add_argument("--study", metavar="ID", help="analyse a study from the store")
    p.add_argument("--dv", metavar="COL[,COL...]",
                   help="dependent variable column(s) (with --study default: kb_gap_mean, kb_gap_ticks_pct, "
                        "interrupts, interrupts_per_selection, ticks, robot_in_fov_pct)")
    p.add_argument("--within", metavar="A,B", help="the two within factors, e.g. robot,kitchen")
    p.add_argument("--subject", metavar="COL", help="subject (participant) id column")
    p.add_argument("--out", metavar="DIR", type=Path, help="output folder (created if needed)")
    p.add_argument("--database-url", metavar="URL",
                   help="with --study: SQLAlchemy URL of the store (default: the one steakhouse serve uses)")
    p.set_defaults(handler=handle, subparser=p)


def handle(args: argparse.Namespace) -> int:
    """Run the analysis; usage problems raise ``UsageError`` (exit code 2)."""
    if args.study is not None:
        return _handle_study(args)
    if args.database_url is not None:
        raise UsageError("--database-url goes with --study")
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


def _handle_study(args: argparse.Namespace) -> int:
    """Export the stored study and analyse its cells."""
    given = [flag for flag in ("within", "subject") if getattr(args, flag) is not None]
    if given:
        raise UsageError(f"--study uses within = robot,kitchen and subject = participant; drop "
                         f"{', '.join('--' + g for g in given)}")
    if args.out is None:
        raise UsageError("--study needs --out")

    from analysis.errors import AnalysisInputError
    from analysis.study import DEFAULT_MEASURES, analyze_study
    from server.commands.export import database_url

    measures = _names(args.dv, "--dv") if args.dv is not None else list(DEFAULT_MEASURES)
    try:
        done = analyze_study(database_url(args.database_url), args.study, args.out, measures)
    except AnalysisInputError as exc:
        raise UsageError(f"study {args.study}: {exc}") from exc
    left_out = done.export.dataset.excluded
    for m in done.result.measures:
        print(f"{m.measure}: n = {m.n_used} of {m.n_total} subjects, {len(m.excluded)} excluded")
    for row in left_out.itertuples():
        print(f"left out: participant {row.participant} ({row.category}): {row.reason}")
    print(f"wrote {len(done.result.files) + len(done.export.files)} files to {done.result.out_dir}")
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
