"""Where the suite's CPU goes (docs/testing.md, "Where the time goes").

As a pytest plugin it records, for every test, the CPU time its worker process spent (user + system, set-up and
tear-down included), the CPU time of the child processes reaped meanwhile (server processes, command-line runs,
nginx; a child's time is counted when it is reaped, so a long-lived child such as a worker's Chromium lands on the
test during which it ended), and the wall time, one JSON line per test in ``DIR/<worker>.jsonl``. Run as a script
it sums those files by test, by module and by package, and prints each worker's busy time::

    PYTHONPATH=tests/tools .venv/bin/python -m pytest -n 4 --dist worksteal -p cpu_profile --cpu-profile=DIR
    .venv/bin/python tests/tools/cpu_profile.py DIR [--top N]
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import sys
import time
from collections import defaultdict
from collections.abc import Callable, Generator, Iterable
from dataclasses import asdict, dataclass
from pathlib import Path

import pytest


@dataclass(frozen=True)
class Spent:
    """One test's cost: its worker's CPU seconds, its reaped children's CPU seconds, its wall seconds, and when it
    began (seconds since the epoch; 0 in files written before it was kept)."""

    test: str
    worker: str
    own: float
    children: float
    wall: float
    start: float = 0.0

    @property
    def cpu(self) -> float:
        return self.own + self.children


def _cpu() -> tuple[float, float]:
    own = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime, children.ru_utime + children.ru_stime


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption("--cpu-profile", metavar="DIR", required=True,
                     help="folder for one JSON line per test: CPU of the worker and its children, wall time")


def pytest_configure(config: pytest.Config) -> None:
    Path(config.getoption("--cpu-profile")).mkdir(parents=True, exist_ok=True)


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_protocol(item: pytest.Item) -> Generator[None, None, None]:
    own, children, wall, start = *_cpu(), time.perf_counter(), time.time()
    yield
    own_after, children_after = _cpu()
    worker = os.environ.get("PYTEST_XDIST_WORKER", "main")
    spent = Spent(item.nodeid, worker, own_after - own, children_after - children, time.perf_counter() - wall,
                  start)
    # One line as each test ends, so a run that is stopped keeps what it measured.
    with (Path(item.config.getoption("--cpu-profile")) / f"{worker}.jsonl").open("a") as out:
        out.write(json.dumps(asdict(spent)) + "\n")


def read(folder: Path) -> list[Spent]:
    return [Spent(**json.loads(line)) for path in sorted(folder.glob("*.jsonl"))
            for line in path.read_text().splitlines() if line]


def _module(test: str) -> str:
    return test.split("::", 1)[0]


def _package(test: str) -> str:
    return "/".join(_module(test).split("/")[:2])


def _by(rows: Iterable[Spent], group_of: Callable[[str], str]) -> list[tuple[str, float, float, int]]:
    """(group, CPU, wall, tests) per group of tests, most CPU first."""
    cpu: dict[str, float] = defaultdict(float)
    wall: dict[str, float] = defaultdict(float)
    count: dict[str, int] = defaultdict(int)
    for row in rows:
        group = group_of(row.test)
        cpu[group] += row.cpu
        wall[group] += row.wall
        count[group] += 1
    return sorted(((g, cpu[g], wall[g], count[g]) for g in cpu), key=lambda r: -r[1])


def report(rows: list[Spent], top: int) -> str:
    lines = [f"{len(rows)} tests: worker CPU {sum(r.own for r in rows):.1f} s, reaped children's CPU "
             f"{sum(r.children for r in rows):.1f} s, wall {sum(r.wall for r in rows):.1f} s (summed over workers)",
             "", "busy time per worker (sum of its tests' wall seconds):"]
    busy: dict[str, float] = defaultdict(float)
    began: dict[str, float] = defaultdict(lambda: float("inf"))
    ended: dict[str, float] = defaultdict(float)
    for row in rows:
        busy[row.worker] += row.wall
        began[row.worker] = min(began[row.worker], row.start)
        ended[row.worker] = max(ended[row.worker], row.start + row.wall)
    lines += [f"  {worker:6} {seconds:7.1f} s" for worker, seconds in sorted(busy.items())]
    if all(row.start for row in rows):
        lines += ["", "each worker's first test began and its last test ended (seconds after the run's first test):"]
        first = min(began.values())
        lines += [f"  {w:6} {began[w] - first:7.1f} s {ended[w] - first:7.1f} s" for w in sorted(busy)]
    lines += ["", f"{'CPU s':>7} {'own':>6} {'child':>6} {'wall s':>7}  test (the {top} costliest in CPU)"]
    for row in sorted(rows, key=lambda r: -r.cpu)[:top]:
        lines.append(f"{row.cpu:7.1f} {row.own:6.1f} {row.children:6.1f} {row.wall:7.1f}  {row.test}")
    for title, group_of, shown in (("package", _package, None), ("module", _module, top)):
        lines += ["", f"{'CPU s':>7} {'wall s':>7} {'tests':>5}  {title}"]
        lines += [f"{c:7.1f} {w:7.1f} {n:5d}  {g}" for g, c, w, n in _by(rows, group_of)[:shown]]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description="Sum a suite's per-test CPU and wall time by test, module and "
                                                 "package (the files written by -p cpu_profile --cpu-profile=DIR).")
    parser.add_argument("folder", type=Path, help="the --cpu-profile folder of a run")
    parser.add_argument("--top", type=int, default=25, help="how many tests and modules to list (default 25)")
    args = parser.parse_args(argv)
    rows = read(args.folder) if args.folder.is_dir() else []
    if not rows:
        parser.error(f"{args.folder}: no *.jsonl files of a run with -p cpu_profile --cpu-profile={args.folder}")
    print(report(rows, args.top))
    return 0


if __name__ == "__main__":
    sys.exit(main())
