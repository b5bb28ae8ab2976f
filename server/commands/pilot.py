"""``steakhouse pilot``: simulated participants through the real server, stored as pilot participants.

    steakhouse pilot --study study_config/paper_study.yaml --participants 28 [--database-url URL] [--jobs J]
        [--realtime] [--seed S] [--url URL --admin-token TOKEN] [--config pilot.yaml] [--set name=value ...]
        [--script hold_key|tap_key|random_task|one_key]

Without ``--url`` the server is started on 127.0.0.1 (a free port) for the study file and the store, and
stopped at the end. Pilot participants are joined with the admin token, so they are marked as pilots in the
store (balanced among themselves, never counted for real participants, left out of ``export`` / ``analyze``
unless ``--include-pilot``). By default their trials step as soon as the robot decided and the simulated
participant acted; ``--realtime`` keeps the study's tick rate. Running the same command again (same ``--seed``)
rejoins the same simulated participants: unfinished ones go on where they stopped. The simulated participant: ``pilot``
(docs/pilot.md); its parameters: ``pilot.config``. At the end it prints, per robot × kitchen, who did the work in the
main rounds (``pilot.report``): the participant's share of dishes and task steps, refused steps, steps with no
executable action, think time and exclusions.
"""

from __future__ import annotations

import argparse
import asyncio
import os
import sys
import time
from pathlib import Path
from typing import Any

from server.cli import UsageError


def register(subparsers: Any) -> None:
    p = subparsers.add_parser(
        "pilot", help="run simulated participants through the real server (rehearse a study)",
        description="Run N simulated participants through the study's participant flow and websocket protocol "
                    "(join, consent, quiz, practice, every round, every questionnaire, end page) against the "
                    "real server, stored as pilot participants.",
        epilog="example: steakhouse pilot --study study_config/paper_study.yaml --participants 28 --jobs 6")
    p.add_argument("--study", metavar="FILE", type=Path, required=True, help="the study YAML file")
    p.add_argument("--participants", metavar="N", type=int, required=True, help="simulated participants to run")
    p.add_argument("--database-url", metavar="URL",
                   help="store of the started server (default: the one steakhouse serve uses)")
    p.add_argument("--jobs", metavar="J", type=int,
                   help="participants at a time (default: the CPU count, one per robot worker of a started "
                        "server: more only queue robot decisions behind each other)")
    p.add_argument("--realtime", action="store_true", help="trials at the study's tick rate (default: as fast "
                   "as the robot decides and the simulated participant acts)")
    p.add_argument("--seed", metavar="S", type=int, default=0, help="seed of the simulated participants (default 0)")
    p.add_argument("--url", metavar="URL", help="use this running server instead of starting one")
    p.add_argument("--admin-token", metavar="TOKEN",
                   help="with --url: the server's admin token (default: $STEAKHOUSE_ADMIN_TOKEN)")
    p.add_argument("--workers", metavar="N", type=int,
                   help="robot worker processes of the started server (default: the server's default)")
    p.add_argument("--config", metavar="FILE", type=Path, help="YAML file of simulated-participant parameters")
    p.add_argument("--set", metavar="NAME=VALUE", action="append", default=[], dest="settings",
                   help="one simulated-participant parameter (repeatable; overrides --config)")
    p.add_argument("--script", choices=["hold_key", "tap_key", "random_task", "one_key"],
                   help="participants who game the engagement rules instead of the simulated participant, sending "
                        "what the browser sends: hold '.', tap '.' (script_tap_seconds), a random enabled task "
                        "every script_every_seconds, or one key per round (recruiting ids pilot-SCRIPT-S-i)")
    p.add_argument("--server-log", metavar="FILE", type=Path, help="the started server's log (default: none)")
    p.set_defaults(handler=handle, subparser=p)


def handle(args: argparse.Namespace) -> int:
    from pilot.config import PilotConfigError, load_config, parse_setting
    from server.commands.export import database_url
    from study_config.catalog import load_one
    from study_config.study import StudyConfigError

    if args.participants < 1:
        raise UsageError("--participants must be at least 1")
    if args.jobs is None:
        args.jobs = os.cpu_count() or 1
    if args.jobs < 1:
        raise UsageError("--jobs must be at least 1")
    if args.url is None and args.admin_token is not None:
        raise UsageError("--admin-token goes with --url")
    if args.url is not None and args.database_url is not None:
        raise UsageError("--database-url is for the started server; a running server (--url) has its own store")
    try:
        config = load_config(args.config, dict(parse_setting(s) for s in args.settings))
    except PilotConfigError as exc:
        raise UsageError(str(exc)) from exc
    if not args.study.is_file():
        raise UsageError(f"--study {args.study}: no such file")
    try:
        loaded = load_one(args.study)
    except StudyConfigError as exc:
        for problem in exc.problems:
            print(problem, file=sys.stderr)
        return 1
    if args.url is not None:
        token = args.admin_token or os.environ.get("STEAKHOUSE_ADMIN_TOKEN")
        if not token:
            raise UsageError("--url needs the server's admin token (--admin-token or STEAKHOUSE_ADMIN_TOKEN)")
        return _run(args, loaded, config, args.url.rstrip("/"), token)

    from pilot.server_process import serve

    url = database_url(args.database_url)
    with serve(args.study, url, args.workers, args.server_log) as server:
        print(f"server started on {server.url} (pid {server.pid}), store {url}", file=sys.stderr)
        return _run(args, loaded, config, server.url, server.admin_token)


def _run(args: argparse.Namespace, loaded: Any, config: Any, base_url: str, token: str) -> int:
    from pilot import report
    from pilot.client import Seat, tls_context
    from pilot.progress import Progress
    from pilot.run import run_pilot
    from pilot.scripts import Script

    script = (Script(args.script, every_seconds=config.script_every_seconds, tap_seconds=config.script_tap_seconds)
              if args.script else None)
    seat = Seat(base_url, token, loaded, config, pace="realtime" if args.realtime else "fast", script=script)
    progress = Progress(args.participants, "pilot")
    started = time.monotonic()
    load_before = os.getloadavg()[0]
    prefix = f"pilot-{args.script}" if args.script else "pilot"
    names = [f"{prefix}-{args.seed}-{i + 1}" for i in range(args.participants)]
    result = asyncio.run(run_pilot(seat, args.participants, args.jobs, args.seed, progress, names))
    seconds = time.monotonic() - started
    trials = sum(o.trials for o in result.outcomes)
    interrupts = sum(o.interrupts for o in result.outcomes)
    print(f"pilot of study {loaded.id}: {len(result.outcomes)} of {args.participants} simulated participants "
          f"finished ({sum(o.completed for o in result.outcomes)} completed), {trials} trials "
          f"({health_summary(result.invalid_trials, result.low_engagement_trials)}), {interrupts} "
          f"interrupts, in {seconds:.1f} s (load average {load_before:.2f} at start, "
          f"{os.getloadavg()[0]:.2f} at end, {os.cpu_count()} CPUs)")
    for failure in result.failures:
        print(f"failed: {failure}", file=sys.stderr)
    rows, screened = report.fetch(base_url, token, loaded.id, names, verify=tls_context())
    print(f"\nmain rounds per robot × kitchen ({loaded.study.timing.mode}, "
          f"{'realtime' if args.realtime else 'fast'} pace{', script ' + args.script if args.script else ''}):")
    print(report.markdown(rows, screened))
    print(f"analyse with: steakhouse analyze --study {loaded.id} --include-pilot --out results/{loaded.id}-pilot")
    return 1 if result.failures else 0


def health_summary(invalid: int | None, low: int | None) -> str:
    """How many trials the analysis will leave out, as the server marked them."""
    if invalid is None or low is None:
        return "invalid and low-engagement trials not counted: the server's participant list could not be read"
    text = f"{invalid} robot-invalid, {low} low-engagement"
    return text + (": left out of the analysis unless --include-invalid" if invalid or low else "")
