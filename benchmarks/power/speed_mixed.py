"""How long ``steakhouse power`` takes on a mixed design, before and after the mixed ANOVA ran on every resample at
once, in one run (the machine is shared: compare the ratio, not the seconds across runs).

Needs a stored study with pilot participants and a factor between participants, e.g. the field of view between ×
robot × kitchen pilot of docs/benchmarks.md:

    steakhouse pilot --study benchmarks/power/power_mixed.yaml --participants 16 --jobs 2 \
        --database-url sqlite:///power_mixed.sqlite3
    python benchmarks/power/speed_mixed.py --database-url sqlite:///power_mixed.sqlite3 --study power_mixed \
        --n 8,12,16,20,24,32,40,48

Runs ``power_study`` as ``steakhouse power --jobs 1`` runs it (export, simulations, plot, report) twice: first with
the one-resample-at-a-time path it replaced (``mixed_anova_table`` on each resample, as the code before did),
then as it is (``analysis.power_analysis.mixed_power.mixed_pvalues`` on all resamples at once), and prints the
wall-clock and CPU seconds of each, their ratio, and whether both wrote the same ``power.csv`` (same seed, same
resamples: the same power, not only the same to Monte-Carlo error).
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any
from unittest import mock

import numpy as np
import pandas as pd


def timed(run: Callable[[], Any]) -> tuple[Any, float, float]:
    wall, cpu = time.perf_counter(), time.process_time()
    value = run()
    return value, time.perf_counter() - wall, time.process_time() - cpu


def one_at_a_time(stack: np.ndarray, slots: Sequence[int], n_groups: int, levels: Sequence[int],
                  within: Sequence[str], ss_type: int = 3) -> tuple[np.ndarray, np.ndarray]:
    """The path before: ``mixed_anova_table`` on each resample (F and the p read)."""
    from analysis.statistics.mixed_anova import mixed_anova_table

    tables = [mixed_anova_table(sample, slots, n_groups, levels, within, "between", intervals=False,
                                ss_type=ss_type) for sample in stack]
    return (np.stack([t["F"].to_numpy(dtype=float) for t in tables]),
            np.stack([t["p_read"].to_numpy(dtype=float) for t in tables]))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--database-url", required=True)
    parser.add_argument("--study", required=True)
    parser.add_argument("--n", default="8,12,16,20,24,32,40,48")
    parser.add_argument("--simulations", type=int, default=1000)
    args = parser.parse_args()
    from analysis.pipeline.study_power import power_study

    ns = [int(x) for x in args.n.split(",")]
    print(f"load average at start {os.getloadavg()[0]:.2f} ({os.cpu_count()} CPUs)")
    with tempfile.TemporaryDirectory() as tmp:
        def run(name: str) -> tuple[pd.DataFrame, float, float]:
            result, wall, cpu = timed(lambda: power_study(args.database_url, args.study, Path(tmp) / name, ns,
                                                          simulations=args.simulations, jobs=1))
            return result.table, wall, cpu

        with mock.patch("analysis.power_analysis.mixed_power.mixed_pvalues", one_at_a_time):
            before, wall_before, cpu_before = run("before")
        after, wall_after, cpu_after = run("after")
    measures = before["measure"].nunique()
    print(f"power_study, {measures} measures × n {args.n} × {args.simulations} simulations, --jobs 1, plots:")
    print(f"  one resample at a time: {wall_before:.1f} s wall, {cpu_before:.1f} s CPU")
    print(f"  all resamples at once:  {wall_after:.1f} s wall, {cpu_after:.1f} s CPU")
    print(f"  ratio before / after: {wall_before / wall_after:.1f}× wall, {cpu_before / cpu_after:.1f}× CPU; "
          f"same power.csv: {before.equals(after)}")
    print(f"load average at end {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
