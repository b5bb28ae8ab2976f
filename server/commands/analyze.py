"""``steakhouse analyze``: repeated-measures analysis of a long CSV or of a stored study.

    steakhouse analyze --csv cells.csv --dv ticks,interrupts --within robot,kitchen \\
        --subject participant --out results/ [--levels robot=fov_aware,baseline] [--ratings q.trust=1..7]
    steakhouse analyze --study paper_study --out results/ [--dv kb_gap_mean,ticks] [--include-invalid]
        [--database-url URL] [--include-pilot]

The CSV has one row per subject and within cell, with one to three within factors. Levels are taken in the order
they first appear unless ``--levels`` gives it. A stored study is first exported to ``<out>/data/``
(``analysis.exports.study_export``) and analysed with the factors, level order, horizon and scales its configuration
declares (``analysis.pipeline.analyze_study``). Output files are listed in ``analysis.pipeline.analyze_long``. A test
that cannot be computed is reported as not testable with the reason (a warning on stderr); the exit code is still 0.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from server.cli import UsageError


def register(subparsers: Any) -> None:
    """Add the ``analyze`` subcommand to the ``steakhouse`` parser."""
    p = subparsers.add_parser(
        "analyze",
        help="repeated-measures ANOVA with sphericity corrections, follow-ups, data quality, plots and report",
        description=(
            "Repeated-measures ANOVA of each --dv on one to three --within factors (Mauchly's test, "
            "Greenhouse-Geisser and Huynh-Feldt corrections, effect sizes with CIs), simple main effects of every "
            "factor, Holm-adjusted pairwise comparisons for factors with more than two levels, rank tests for "
            "ratings, descriptives with within-subject 95% CIs, plots, and a Markdown/HTML report that opens with "
            "data quality (who was left out and why, invalid trials, censored cells, order effects, residual "
            "normality). With --study the stored study is exported to OUT/data/ first and analysed with the "
            "design its configuration declares."
        ),
        epilog="examples: steakhouse analyze --csv cells.csv --dv ticks,interrupts "
        "--within robot,kitchen --subject participant --out results/ | "
        "steakhouse analyze --study paper_study --out results/",
    )
    source = p.add_mutually_exclusive_group(required=True)
    source.add_argument("--csv", metavar="FILE", type=Path, help="long table, one row per subject and cell")
    source.add_argument("--study", metavar="ID", help="analyse a study from the store")
    p.add_argument("--dv", metavar="COL[,COL...]",
                   help="dependent variable column(s) (with --study default: kb_diff_freq, kb_diff_avg, "
                        "interrupts, interrupts_per_selection, ticks, robot_in_fov_pct, kb_gap_mean, kb_gap_ticks_pct "
                        "and the study's scales)")
    p.add_argument("--within", metavar="A[,B[,C]]", help="one to three within factors, e.g. robot,kitchen")
    p.add_argument("--subject", metavar="COL", help="subject (participant) id column")
    p.add_argument("--between", metavar="COL",
                   help="with --csv: a factor between participants (one level each): mixed (split-plot) ANOVA")
    p.add_argument("--model", choices=("anova", "lmm"), default="anova",
                   help="anova (default): the (mixed) ANOVA on complete cases; lmm: also a linear mixed model "
                        "(statsmodels, random intercept per participant) on every row, for unbalanced or "
                        "incomplete data, its formula printed")
    p.add_argument("--ss-type", type=int, choices=(2, 3), default=3,
                   help="mixed designs: sums of squares of type 3 (default, as R's afex and JASP) or 2 (as "
                        "pingouin, and afex or JASP set to type II); the same with equal groups")
    p.add_argument("--follow-up-error", choices=("pooled", "per-group"), default="pooled",
                   help="mixed designs: the error of the follow-ups within each group: the within-group covariance "
                        "pooled over the groups, N - G df (default, as emmeans on an afex model), or each group's "
                        "own (as analysing each group alone)")
    p.add_argument("--out", metavar="DIR", type=Path, help="output folder (created if needed)")
    p.add_argument("--levels", metavar="FACTOR=A,B,...", action="append", default=[],
                   help="with --csv: the order of a factor's levels (repeat per factor; default: order of first "
                        "appearance)")
    p.add_argument("--ratings", metavar="COL[=MIN..MAX][,...]",
                   help="with --csv: columns that are ratings (rank tests beside the ANOVA), with their scale")
    p.add_argument("--include-invalid", action="store_true",
                   help="keep trials the server marked invalid or low-engagement (listed either way)")
    p.add_argument("--include-pilot", action="store_true",
                   help="with --study: analyse simulated pilot participants too (steakhouse pilot; left out by "
                        "default)")
    p.add_argument("--no-plots", action="store_true", help="skip the plots (the slowest part of a run)")
    p.add_argument("--seed", metavar="N", type=int, default=0,
                   help="seed of the bootstrap CI of generalized eta squared and of the plots' jitter (default 0)")
    p.add_argument("--database-url", metavar="URL",
                   help="with --study: SQLAlchemy URL of the store (default: the one steakhouse serve uses)")
    p.set_defaults(handler=handle, subparser=p)


def handle(args: argparse.Namespace) -> int:
    """Run the analysis; usage problems raise ``UsageError`` (exit code 2)."""
    include = frozenset(({"invalid", "low_engagement"} if args.include_invalid else set())
                        | ({"pilot"} if args.include_pilot else set()))
    if args.study is not None:
        return _handle_study(args, include)
    if args.database_url is not None:
        raise UsageError("--database-url goes with --study")
    if args.include_pilot:
        raise UsageError("--include-pilot goes with --study")
    if args.between is not None and not args.between.strip():
        raise UsageError("--between needs a column name")
    missing = [flag for flag in ("dv", "within", "subject", "out") if getattr(args, flag) is None]
    if missing:
        raise UsageError(f"--csv needs {', '.join('--' + m for m in missing)}")
    from server.commands.export import check_out

    check_out(args.out, "plots")
    measures = _names(args.dv, "--dv")
    within = _names(args.within, "--within")
    if not 1 <= len(within) <= 3:
        raise UsageError(f"--within takes one to three factors (A, A,B or A,B,C), got {args.within!r}")
    df = _read_csv(args.csv)

    from analysis.pipeline.analyze_long import analyze_long
    from analysis.preparation.levels import parse_level_option
    from analysis.preparation.options import AnalysisOptions
    from analysis.source.input_errors import AnalysisInputError

    try:
        options = AnalysisOptions(levels=parse_level_option(args.levels), ratings=_ratings(args.ratings),
                                  include=include, seed=args.seed, plots=not args.no_plots,
                                  between=args.between.strip() if args.between else None,
                                  lmm=args.model == "lmm", ss_type=args.ss_type,
                                  follow_up_error=args.follow_up_error)
        result = analyze_long(df, measures, within, args.subject, args.out, options)
    except AnalysisInputError as exc:
        raise UsageError(f"{args.csv}: {exc}") from exc
    _print(result)
    return 0


def _handle_study(args: argparse.Namespace, include: frozenset[str]) -> int:
    """Export the stored study and analyse its cells."""
    given = [flag for flag in ("within", "subject", "levels", "ratings", "between") if getattr(args, flag)]
    if given:
        raise UsageError(f"--study takes the design from the study; drop {', '.join('--' + g for g in given)}")
    if args.out is None:
        raise UsageError("--study needs --out")
    from server.commands.export import check_out

    check_out(args.out, "data", "plots")

    from analysis.pipeline.analyze_study import analyze_study
    from analysis.source.input_errors import AnalysisInputError
    from server.commands.export import database_url

    measures = _names(args.dv, "--dv") if args.dv is not None else None
    try:
        done = analyze_study(database_url(args.database_url), args.study, args.out, measures, include, args.seed,
                             plots=not args.no_plots, lmm=args.model == "lmm", ss_type=args.ss_type,
                             follow_up_error=args.follow_up_error)
    except AnalysisInputError as exc:
        raise UsageError(f"study {args.study}: {exc}") from exc
    for row in done.export.dataset.excluded.itertuples():
        print(f"left out: participant {row.participant} ({row.category}): {row.reason}")
    _print(done.result, len(done.export.files))
    return 0


def _print(result: Any, extra_files: int = 0) -> None:
    for m in result.measures:
        print(f"{m.measure}: n = {m.n_used} of {m.n_total} subjects, {len(m.excluded)} excluded")
    for formula in dict.fromkeys(getattr(result, "formulas", ())):
        print(f"linear mixed model: {formula}")
    for warning in result.warnings:
        print(f"warning: {warning}", file=sys.stderr)
    print(f"wrote {len(result.files) + extra_files} files to {result.out_dir}")


def _names(value: str, flag: str) -> list[str]:
    names = [name.strip() for name in value.split(",")]
    if not all(names):
        raise UsageError(f"{flag} {value!r} has an empty column name")
    return names


def _ratings(value: str | None) -> dict[str, tuple[float, float]]:
    """``fluency=1..7,trust`` → ``{"fluency": (1, 7), "trust": (-inf, inf)}``."""
    out: dict[str, tuple[float, float]] = {}
    for part in _names(value, "--ratings") if value else []:
        name, sep, bounds = part.partition("=")
        low, dots, high = bounds.partition("..")
        try:
            out[name] = (float(low), float(high)) if sep else (float("-inf"), float("inf"))
        except ValueError:
            raise UsageError(f"--ratings {part!r}: expected COL or COL=MIN..MAX (e.g. trust=1..7)") from None
        if sep and (not dots or out[name][0] >= out[name][1]):
            raise UsageError(f"--ratings {part!r}: expected COL=MIN..MAX with MIN < MAX")
    return out


def _read_csv(path: Path) -> Any:
    import pandas as pd

    if not path.is_file():
        raise UsageError(f"--csv {path}: no such file")
    try:
        return pd.read_csv(path)
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as exc:
        raise UsageError(f"--csv {path}: not a readable CSV table ({exc})") from exc
