"""Server load: N simulated participants playing full trials at once over real websockets.

    .venv/bin/python benchmarks/load/run.py --participants 20 --seconds 60 [--json]

Starts ``steakhouse serve`` on 127.0.0.1 (a free port) with a study of its own (the FOV-aware robot in the
paper's two kitchens, 5 Hz, two orders, 400 ticks, one questionnaire item) on a temporary SQLite file (or
``--database postgresql``: a database created for the run and dropped after it), runs ``--participants``
seats for ``--seconds`` (each seat is one participant after another: join, consent, instructions, both
trials, questionnaires, completion), then stops the clients, stops the server and reads the store.

Reports the server's own tick lateness p50 / p99, missed ticks and robot deadline misses (from the stored
ticks and events), the heartbeat round trip p99 (clients), server and robot-worker CPU and memory, rows
written and errors (client errors, ``error`` events in the store, ERROR lines in the server log). With
``--json`` it prints one JSON object. With ``--max-live-trials C`` the server admits at most C live trials
(``server.game.admission``; the others wait for a slot) and the report adds the waits and the trials the
server marked invalid (``admission_metrics``). Bounded: the clients stop at ``--seconds``, everything else has
timeouts.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import sys
import tempfile
import time
from datetime import UTC, datetime, timedelta
from pathlib import Path
from typing import Any

import yaml

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parents[1])]

from admission_metrics import admission_metrics  # noqa: E402
from bench_server import DEFAULT_POSTGRES, BenchServer, ResourceSampler, temporary_database  # noqa: E402
from simulated_participant import run_load  # noqa: E402
from store_metrics import percentile, store_metrics  # noqa: E402

from server.settings import default_workers  # noqa: E402

STUDY_ID = "load"


def write_study(folder: Path, *, robot: str, kitchens: list[str], tick_rate: float, horizon: int,
                orders: int) -> Path:
    study = {
        "id": STUDY_ID, "title": "Load benchmark", "kitchens": kitchens, "robots": [robot],
        "factors": ["kitchen"] if len(kitchens) > 1 else ["robot"],
        "timing": {"tick_rate_hz": tick_rate}, "world": {"orders": orders, "horizon": horizon},
        "questionnaires": [{"id": "q", "items": [{"id": "fluency", "text": "Fluent?",
                                                   "scale": {"min": 1, "max": 7}}]}],
        "reconnect": {"grace_seconds": 60, "after_grace": "abandon"},
    }
    path = folder / f"{STUDY_ID}.yaml"
    path.write_text(yaml.safe_dump(study), encoding="utf-8")
    return path


def loadavg() -> list[float]:
    return [round(v, 2) for v in os.getloadavg()]


def run(args: argparse.Namespace) -> dict[str, Any]:
    kitchens = [k for k in args.kitchens.split(",") if k]
    with tempfile.TemporaryDirectory(prefix="steakhouse-load-") as tmp:
        folder = Path(args.keep) if args.keep else Path(tmp)
        folder.mkdir(parents=True, exist_ok=True)
        study = write_study(folder, robot=args.robot, kitchens=kitchens, tick_rate=args.tick_rate,
                            horizon=args.horizon, orders=args.orders)
        before = loadavg()
        with temporary_database(args.database, folder, args.postgres_url) as url:
            env = {"STEAKHOUSE_ADMISSION_MAX_WAIT_S": str(args.max_wait)}
            if args.max_live_trials is not None:
                env["STEAKHOUSE_MAX_LIVE_TRIALS"] = str(args.max_live_trials)
            server = BenchServer(study=study, database_url=url, workers=args.workers, log=folder / "server.log",
                                 env=env)
            with server:
                started = time.monotonic()
                measure_from = datetime.now(UTC) + timedelta(seconds=args.warmup)
                with ResourceSampler(server.pid, start_after=args.warmup) as sampler:
                    stats = asyncio.run(run_load(server.url, STUDY_ID, args.participants,
                                                 args.warmup + args.seconds, seed=args.seed, ramp_s=args.ramp))
                wall = time.monotonic() - started
            log_errors = server.log_errors()
            measured = store_metrics(url, 1000.0 / args.tick_rate, measure_from)
            admitted = admission_metrics(url)
        after = loadavg()
    client_errors = stats.errors
    errors = len(client_errors) + measured["server_error_events"] + len(log_errors)
    return {
        "participants": args.participants, "seconds": args.seconds, "warmup_s": args.warmup,
        "wall_s": round(wall, 1),
        "robot": args.robot, "kitchens": kitchens, "tick_rate_hz": args.tick_rate, "database": args.database,
        "robot_workers": args.workers, "cpus": os.cpu_count(),
        "p50_tick_lateness_ms": measured["p50_tick_lateness_ms"],
        "p99_tick_lateness_ms": measured["p99_tick_lateness_ms"],
        "max_tick_lateness_ms": measured["max_tick_lateness_ms"],
        "missed_ticks": measured["missed_ticks"],
        "deadline_misses": measured["deadline_misses"],
        "ticks_robot_missed": measured["ticks_robot_missed"],
        "p50_decision_ms": measured["p50_decision_ms"], "p99_decision_ms": measured["p99_decision_ms"],
        "p99_rtt_ms": percentile(stats.pong_rtt_ms, 0.99), "p50_rtt_ms": percentile(stats.pong_rtt_ms, 0.50),
        "p99_ack_rtt_ms": percentile(stats.ack_rtt_ms, 0.99),
        **sampler.summary(),
        "ticks": measured["ticks"], "trials": measured["trials"],
        "warmup_ticks": measured["warmup_ticks"],
        "warmup_p99_tick_lateness_ms": measured["warmup_p99_tick_lateness_ms"],
        "warmup_deadline_misses": measured["warmup_deadline_misses"],
        "joined": stats.joined, "trials_ended": stats.trials_ended, "completed": stats.completed,
        "messages_received": stats.messages, "late_messages": stats.late_messages,
        "rows_written": measured["rows_written"], "rows": measured["rows"],
        "errors": errors,
        "error_samples": (client_errors[:5] + [str(p) for p in measured["server_error_samples"][:5]]
                          + log_errors[:5]),
        "loadavg_before": before, "loadavg_after": after,
        "max_live_trials": args.max_live_trials, "waiting_messages": stats.waiting_messages,
        "turned_away": stats.turned_away, **admitted,
    }


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(description="Server load: N simulated participants over real websockets.")
    p.add_argument("--participants", type=int, default=10, help="simultaneous participants (seats)")
    p.add_argument("--seconds", type=float, default=60.0, help="how long the participants play after the warm-up")
    p.add_argument("--warmup", type=float, default=10.0,
                   help="seconds of play first, left out of the lateness and deadline numbers (cold planner caches)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--robot", default="fov_aware")
    p.add_argument("--kitchens", default="none_3,mid_2", help="comma-separated kitchens (one trial each)")
    p.add_argument("--tick-rate", type=float, default=5.0)
    p.add_argument("--horizon", type=int, default=400)
    p.add_argument("--orders", type=int, default=2)
    p.add_argument("--workers", type=int, default=default_workers(),
                   help="robot worker processes (default: the server's, two per CPU)")
    p.add_argument("--database", choices=("sqlite", "postgresql"), default="sqlite")
    p.add_argument("--postgres-url", default=os.environ.get("TEST_POSTGRES_URL", DEFAULT_POSTGRES),
                   help="server on which the run's PostgreSQL database is created and dropped")
    p.add_argument("--ramp", type=float, default=2.0, help="seconds over which the seats start")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--max-live-trials", type=int, default=None,
                   help="the server's live-trial cap (default: the server's own, derived from the CPU count)")
    p.add_argument("--max-wait", type=float, default=600.0,
                   help="seconds a participant may wait for a slot before being screened out")
    p.add_argument("--keep", metavar="DIR", help="keep the study, SQLite store and server log in DIR")
    return p


def print_report(result: dict[str, Any]) -> None:
    keys = ["participants", "seconds", "warmup_s", "database", "ticks", "p50_tick_lateness_ms", "p99_tick_lateness_ms",
            "max_tick_lateness_ms", "missed_ticks", "deadline_misses", "warmup_deadline_misses", "p99_decision_ms",
            "p99_rtt_ms",
            "server_cpu_percent", "workers_cpu_percent", "clients_cpu_percent", "other_cpu_percent",
            "server_rss_mb_peak", "workers_rss_mb_peak",
            "rows_written", "joined", "trials_ended", "errors", "loadavg_before", "loadavg_after",
            "max_live_trials", "waits", "wait_outcomes", "p50_wait_s", "p95_wait_s", "max_wait_s", "turned_away",
            "trials_invalid", "max_missed_decisions_pct"]
    for key in keys:
        print(f"{key:<24}{result[key]}")
    for sample in result["error_samples"]:
        print(f"  error: {sample}")


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    if args.participants < 1 or args.seconds <= 0:
        parser().error("--participants must be ≥ 1 and --seconds > 0")
    result = run(args)
    if args.json:
        print(json.dumps(result))
    else:
        print_report(result)
    return 0


if __name__ == "__main__":
    sys.exit(main())
