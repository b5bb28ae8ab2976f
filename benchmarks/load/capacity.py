"""Capacity: the largest number of simultaneous participants the server keeps on time on this machine.

    .venv/bin/python benchmarks/load/capacity.py [--counts 5,10,15,20,25,30] [--seconds 60] [--all]

For each N (ascending) one fresh run of ``run.py`` (its own server and store) with the FOV-aware robot at
5 Hz; N passes when, after the warm-up, the server's p99 tick lateness is at most ``--max-p99-ms`` (50),
no robot decision missed its deadline and nothing failed. The server's admission cap is set to N for the
run (``--max-live-trials``): the question is how many live trials the machine carries, not how many the
default cap lets in. Stops at the first N that fails (``--all`` runs
every N). Prints one row per N with the machine's load average before and after its run and the CPU other
processes used during it (``oth cpu%``: other work on the machine skews a row), and the largest passing N.
``--json`` prints the rows as a JSON list instead.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
COLUMNS = [("N", "participants", 4), ("ticks", "ticks", 7), ("p50 ms", "p50_tick_lateness_ms", 8),
           ("p99 ms", "p99_tick_lateness_ms", 8), ("max ms", "max_tick_lateness_ms", 8),
           ("missed", "missed_ticks", 7), ("dl miss", "deadline_misses", 8),
           ("warm dl", "warmup_deadline_misses", 8), ("dec p99", "p99_decision_ms", 8),
           ("rtt p99", "p99_rtt_ms", 8), ("srv cpu%", "server_cpu_percent", 9),
           ("rob cpu%", "workers_cpu_percent", 9), ("oth cpu%", "other_cpu_percent", 9),
           ("srv MB", "server_rss_mb_peak", 7),
           ("rob MB", "workers_rss_mb_peak", 7), ("rows", "rows_written", 7), ("errors", "errors", 7)]


def passes(result: dict[str, Any], max_p99_ms: float) -> bool:
    p99 = result["p99_tick_lateness_ms"]
    return (p99 is not None and p99 <= max_p99_ms and result["deadline_misses"] == 0 and result["errors"] == 0
            and result["ticks"] > 0)


def run_one(n: int, args: argparse.Namespace) -> dict[str, Any]:
    command = [sys.executable, str(HERE / "run.py"), "--participants", str(n), "--seconds", str(args.seconds),
               "--warmup", str(args.warmup), "--robot", args.robot, "--tick-rate", str(args.tick_rate),
               "--database", args.database, "--max-live-trials", str(n), "--json"]
    if args.workers is not None:
        command += ["--workers", str(args.workers)]
    timeout = args.warmup + args.seconds + 240
    done = subprocess.run(command, capture_output=True, text=True, timeout=timeout, check=False)
    if done.returncode != 0:
        raise RuntimeError(f"run.py failed for N={n}:\n{done.stderr[-2000:]}")
    result: dict[str, Any] = json.loads(done.stdout.strip().splitlines()[-1])
    return result


def row(result: dict[str, Any], ok: bool) -> str:
    cells = [f"{'' if result.get(key) is None else result[key]!s:>{width}}" for _, key, width in COLUMNS]
    load = f"{result['loadavg_before'][0]:>5.2f} → {result['loadavg_after'][0]:<5.2f}"
    return "".join(cells) + f"  {'yes' if ok else 'no':>4}  {load}"


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description="Largest N of simultaneous participants kept on time.")
    p.add_argument("--counts", default="5,10,15,20,25,30,35,40")
    p.add_argument("--seconds", type=float, default=60.0, help="measured seconds per run (after the warm-up)")
    p.add_argument("--warmup", type=float, default=10.0)
    p.add_argument("--robot", default="fov_aware")
    p.add_argument("--tick-rate", type=float, default=5.0)
    p.add_argument("--workers", type=int, default=None,
                   help="robot worker processes (default: the server's, two per CPU)")
    p.add_argument("--database", choices=("sqlite", "postgresql"), default="sqlite")
    p.add_argument("--max-p99-ms", type=float, default=50.0)
    p.add_argument("--all", action="store_true", help="run every N, not only up to the first failure")
    p.add_argument("--json", action="store_true")
    args = p.parse_args(argv)
    counts = sorted(int(c) for c in args.counts.split(","))
    print(f"# {args.robot} robot at {args.tick_rate:g} Hz, {args.seconds:g} s measured after {args.warmup:g} s "
          f"warm-up, {args.database}, {os.cpu_count()} CPUs; pass: p99 lateness ≤ {args.max_p99_ms:g} ms, "
          "no deadline miss, no error", file=sys.stderr if args.json else sys.stdout)
    if not args.json:
        print("".join(f"{title:>{width}}" for title, _, width in COLUMNS) + "  pass  load 1-min (before → after)")
    results, best = [], 0
    for n in counts:
        result = run_one(n, args)
        ok = passes(result, args.max_p99_ms)
        result["pass"] = ok
        results.append(result)
        if not args.json:
            print(row(result, ok), flush=True)
        if ok:
            best = n
        elif not args.all:
            break
    if args.json:
        print(json.dumps(results))
    else:
        print(f"largest N passing: {best if best else 'none'}")
        for result in results:
            for sample in result["error_samples"]:
                print(f"  N={result['participants']} error: {sample}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
