#!/usr/bin/env bash
# One command: build the peer's own environment (overcooked-ai 1.1.0 with numpy<2 and scipy, never a
# dependency of the product), then time both worlds in one process. Extra arguments go to bench.py.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
venv="$root/benchmarks/.venv-world"
if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c "import overcooked_ai_py" 2>/dev/null; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install -q "numpy<2" scipy "overcooked-ai==1.1.0"
fi
cd "$root"
PYTHONPATH="$root" "$venv/bin/python" -W ignore "$here/bench.py" "$@" 2>&1 | grep --line-buffered -v -e "Computing MotionPlanner" -e "^Gym has been" -e "^Please upgrade to Gymnasium" -e "^Users of this version of Gym" -e "^See the migration guide"
