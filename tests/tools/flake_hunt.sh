#!/usr/bin/env bash
# The flake hunt (docs/testing.md, "Flake hunt"): the whole suite, from a fresh clone of this checkout's HEAD, run
# RUNS times (default 5) in the suite's own order and then RANDOM_RUNS times (default 1) in a random test order
# (pytest-random-order, bucket "global"), while busy loops keep every core taken. Prints one line per run (pass/fail,
# wall seconds, pytest's summary) as it ends and exits 1 if any run failed; each run's whole output and its tests'
# temporary folders (stores, server logs) stay in the hunt's folder for reading.
#
#   bash tests/tools/flake_hunt.sh [RUNS [RANDOM_RUNS]]        (make flake-hunt RUNS=5 RANDOM_RUNS=1)
set -uo pipefail
runs="${1:-5}"
random_runs="${2:-1}"
for n in "$runs" "$random_runs"; do
  case "$n" in
    ''|*[!0-9]*) echo "usage: bash tests/tools/flake_hunt.sh [RUNS [RANDOM_RUNS]]  (whole numbers of runs)" >&2
                 exit 2 ;;
  esac
done
repo="$(cd "$(dirname "$0")/../.." && pwd)"
hunt="$(mktemp -d /tmp/flake-hunt.XXXXXX)"
git clone -q "$repo" "$hunt/clone" || exit 1
echo "flake hunt of $(git -C "$repo" rev-parse --short HEAD) in $hunt: $runs loaded runs, then $random_runs in random order"

loads=()
stop_loads() { for pid in "${loads[@]}"; do kill "$pid" 2>/dev/null; done; }
trap stop_loads EXIT
for _ in $(seq "$(nproc)"); do
  ( while :; do :; done ) &
  loads+=("$!")
done

failed=0
run() {  # name, extra pytest arguments
  local log="$hunt/$1.log" start status
  start=$(date +%s)
  # Each run's temporary folders (the failed test's store and server log among them) stay for reading.
  (cd "$hunt/clone" && CI=true make test PYTEST_ARGS="--basetemp=$hunt/$1.tmp $2" </dev/null >"$log" 2>&1)
  status=$?
  local summary
  summary=$(grep -E '^=+ .*(passed|failed|error).* in [0-9.]+s' "$log" | tail -1 | tr -d '=')
  printf '%-14s %-4s %5ss %s\n' "$1" "$([ $status -eq 0 ] && echo pass || echo FAIL)" \
    "$(( $(date +%s) - start ))" "${summary:-(no pytest summary: see $log)}"
  [ $status -eq 0 ] || failed=1
}
for i in $(seq "$runs"); do
  run "loaded-$i" ""
done
for i in $(seq "$random_runs"); do
  run "random-order-$i" "--random-order-bucket=global"
done
exit $failed
