"""Statement coverage per package after ``make test`` (docs/testing.md, "Coverage"), checked against a floor.

Reads the ``.coverage`` data file pytest-cov wrote, sums the statements and the executed statements of every
measured file by its top-level package (``planner``, ``server``, ...), prints one row per package and exits 1
when a package falls below its floor in ``tests/tools/coverage_floor.toml``. The floors are what the suite
measured when they were set, rounded down to a whole percent; raise one when the suite covers more.

    .venv/bin/python tests/tools/coverage_floor.py [--data .coverage] [--floors tests/tools/coverage_floor.toml]
"""

from __future__ import annotations

import argparse
import sys
import tomllib
from collections import defaultdict
from pathlib import Path

import coverage

ROOT = Path(__file__).resolve().parents[2]


def per_package(data_file: Path) -> dict[str, tuple[int, int]]:
    """Statements and executed statements per top-level package of the repository."""
    cov = coverage.Coverage(data_file=str(data_file))
    cov.load()
    totals: dict[str, list[int]] = defaultdict(lambda: [0, 0])
    for name in cov.get_data().measured_files():
        path = Path(name).resolve()
        if not path.is_relative_to(ROOT) or path.suffix != ".py":
            continue
        package = path.relative_to(ROOT).parts[0]
        _, statements, _, missing, _ = cov.analysis2(name)
        totals[package][0] += len(statements)
        totals[package][1] += len(statements) - len(missing)
    return {package: (total, run) for package, (total, run) in sorted(totals.items())}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", type=Path, default=ROOT / ".coverage", help="coverage data file")
    parser.add_argument("--floors", type=Path, default=ROOT / "tests/tools/coverage_floor.toml",
                        help="floors per package (percent)")
    args = parser.parse_args(argv)
    if not args.data.is_file():
        parser.error(f"{args.data}: no coverage data (run the tests with --cov first)")
    floors: dict[str, float] = tomllib.loads(args.floors.read_text())["floor"]
    measured = per_package(args.data)
    failed = []
    print(f"{'package':<14}{'statements':>11}{'run':>8}{'cover':>8}{'floor':>7}")
    for package, (total, run) in measured.items():
        percent = 100.0 * run / total if total else 100.0
        floor = floors.get(package)
        mark = "" if floor is None or percent >= floor else "  below the floor"
        print(f"{package:<14}{total:>11}{run:>8}{percent:>7.1f}%{'' if floor is None else f'{floor:>6.0f}%'}{mark}")
        if mark:
            failed.append(package)
    missing = sorted(set(floors) - set(measured))
    if missing:
        print(f"no coverage measured for {', '.join(missing)}", file=sys.stderr)
        return 1
    if failed:
        print(f"coverage below the floor in {', '.join(failed)} (tests/tools/coverage_floor.toml)", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
