#!/usr/bin/env bash
# Planner latency (one core) and the paper's simulation table. Uses the project's environment (make setup).
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
cd "$root"
make -s setup >/dev/null 2>&1
exec "$root/.venv/bin/python" "$root/benchmarks/planner/bench.py" "$@"
