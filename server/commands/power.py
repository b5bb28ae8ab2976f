"""``steakhouse power``: how many participants a study needs, simulated from its pilot participants.

    steakhouse power --study paper_study --n 8,16,28,40,64 --out power/ [--alpha 0.05] [--simulations 1000]
        [--jobs J] [--seed S] [--dv kb_gap_mean,interrupts] [--effect eta2g=0.1] [--include-invalid]
        [--database-url URL]

For each measure and planned test (main effects, interaction, each factor's simple effects) the pilot
participants (``steakhouse pilot``) are resampled with replacement at each n and the test ``analyze`` runs is
run on each sample (:mod:`analysis.power_analysis.within_power`, :mod:`analysis.pipeline.study_power`); with ``--effect
eta2g=0.1`` also each omnibus effect set to that generalized η² (:mod:`analysis.power_analysis.chosen_effect`). A study
with a factor between participants gets the mixed ANOVA's tests, n the total over its groups
(:mod:`analysis.power_analysis.mixed_power`; no ``--effect``). A progress bar (on a terminal) counts
measure × n steps; otherwise a line per measure. Writes power.csv, n_needed.csv, power.png and power.md to
``--out``.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from server.cli import UsageError


def register(subparsers: Any) -> None:
    p = subparsers.add_parser(
        "power", help="simulation power analysis from a study's pilot participants",
        description="Resample the study's pilot participants with replacement at each --n, run the planned tests "
                    "analyze runs, and report power with a Monte-Carlo interval, the n reaching 80 %% and 90 %%, "
                    "and a plot of power against n.",
        epilog="example: steakhouse power --study paper_study --n 8,16,28,40,64 --out power/")
    p.add_argument("--study", metavar="ID", required=True, help="study id in the store")
    p.add_argument("--n", metavar="N[,N...]", required=True, help="sample sizes, e.g. 8,16,28,40,64")
    p.add_argument("--out", metavar="DIR", type=Path, required=True, help="output folder (created if needed)")
    p.add_argument("--alpha", type=float, default=0.05, help="significance level (default 0.05)")
    p.add_argument("--simulations", metavar="K", type=int, default=1000, help="resamples per n (default 1000)")
    p.add_argument("--jobs", metavar="J", type=int, default=1, help="processes (default 1)")
    p.add_argument("--seed", metavar="S", type=int, default=0, help="seed of the resampling (default 0)")
    p.add_argument("--dv", metavar="COL[,COL...]", help="measures (default: those analyze runs by default)")
    p.add_argument("--effect", metavar="eta2g=V",
                   help="also the power of each omnibus effect set to this generalized η² (e.g. eta2g=0.1), "
                        "beside the pilot's own effect sizes")
    p.add_argument("--ss-type", type=int, choices=(2, 3), default=3,
                   help="a design with a factor between participants: sums of squares of type 3 (default, as "
                        "analyze) or 2")
    p.add_argument("--include-invalid", action="store_true", help="keep trials the server marked invalid")
    p.add_argument("--no-plots", action="store_true", help="skip power.png")
    p.add_argument("--database-url", metavar="URL",
                   help="SQLAlchemy URL of the store (default: the one steakhouse serve uses)")
    p.set_defaults(handler=handle, subparser=p)


def parse_ns(text: str) -> list[int]:
    try:
        ns = [int(part) for part in text.split(",") if part.strip()]
    except ValueError:
        raise UsageError(f"--n {text!r}: expected whole numbers separated by commas, e.g. 8,16,28") from None
    if not ns or any(n < 2 for n in ns):
        raise UsageError(f"--n {text!r}: every n must be at least 2")
    return sorted(set(ns))


def handle(args: argparse.Namespace) -> int:
    ns = parse_ns(args.n)
    if not 0 < args.alpha < 1:
        raise UsageError(f"--alpha {args.alpha}: must be between 0 and 1")
    if args.simulations < 10:
        raise UsageError("--simulations must be at least 10")
    if args.jobs < 1:
        raise UsageError("--jobs must be at least 1")
    from server.commands.export import check_out

    check_out(args.out, "data")
    from analysis.pipeline.study_power import power_study
    from analysis.power_analysis.chosen_effect import EffectSize
    from analysis.source.input_errors import AnalysisInputError
    from pilot.progress import Progress
    from server.commands.export import database_url

    measures = [m.strip() for m in args.dv.split(",")] if args.dv else None
    if measures is not None and not all(measures):
        raise UsageError(f"--dv {args.dv!r} has an empty column name")
    include = frozenset({"invalid"} if args.include_invalid else ())
    try:
        effect_size = EffectSize.parse(args.effect) if args.effect else None
    except AnalysisInputError as exc:
        raise UsageError(str(exc)) from exc
    progress = Progress(0, "power")
    try:
        result = power_study(database_url(args.database_url), args.study, args.out, ns,
                             simulations=args.simulations, alpha=args.alpha, jobs=args.jobs, seed=args.seed,
                             measures=measures, include=include, plots=not args.no_plots,
                             effect_size=effect_size, on_step=progress.advance, ss_type=args.ss_type,
                             on_measure=lambda name: None if progress.tty else print(
                                 f"power: {name} done ({progress.done}/{progress.total} steps)", file=sys.stderr,
                                 flush=True),
                             on_start=lambda total: setattr(progress, "total", total))
    except AnalysisInputError as exc:
        raise UsageError(f"study {args.study}: {exc}") from exc
    progress.close()
    for measure, reason in result.not_simulated.items():
        print(f"warning: {measure} not simulated: {reason}", file=sys.stderr)
    for row in result.needed.itertuples(index=False):
        size = "" if row.scenario == "pilot" else f" with {row.scenario}"
        print(f"{row.measure} / {row.test}{size}: 80 % at n = {_n(row.n_80)}, 90 % at n = {_n(row.n_90)}")
    print(f"from {result.pilot_participants} pilot participants; wrote {len(result.files)} files to {args.out}",
          file=sys.stderr)
    return 0


def _n(value: object) -> str:
    import pandas as pd

    return "beyond the grid" if value is None or pd.isna(value) else str(int(value))  # type: ignore[call-overload]
