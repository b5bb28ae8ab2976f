"""How long ``steakhouse power`` takes, and what the vectorised tests saved.

Needs a stored study with pilot participants, e.g. the 3 robots × 2 kitchens pilot of docs/analysis.md:

    steakhouse pilot --study benchmarks/power/power_3x2.yaml --participants 12 --jobs 2 \
        --database-url sqlite:///power.sqlite3
    python benchmarks/power/speed.py --database-url sqlite:///power.sqlite3 --study power_3x2 --n 8,12,24,36

Prints, per phase, the wall-clock and CPU seconds of this process: the export and preparation of the pilot's
table, the simulations of every measure (``analysis.power_analysis.within_power.measure_power``, default 1000 per n),
the whole ``power_study`` call as ``steakhouse power`` makes it (plots included), and, for comparison, the per-resample
``anova_table`` path the vectorised tests replaced (run on ``--reference-simulations`` resamples per n, with
its time scaled to the same number of simulations as the measured run; the line says so) and whether both gave
the same p values on those resamples.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from collections.abc import Callable, Sequence
from functools import partial
from pathlib import Path
from typing import Any

import numpy as np


def timed(run: Callable[[], Any]) -> tuple[Any, float, float]:
    wall, cpu = time.perf_counter(), time.process_time()
    value = run()
    return value, time.perf_counter() - wall, time.process_time() - cpu


def reference_pvalues(values: np.ndarray, levels: Sequence[int], within: Sequence[str], tests: Sequence[Any]
                      ) -> np.ndarray:
    """The per-resample path: ``anova_table`` on each resample for every effect with more than one df."""
    from analysis.power_analysis.within_power import holm_matrix, one_df_p
    from analysis.statistics.anova import anova_table

    p = np.full((values.shape[0], len(tests)), np.nan)
    for t, test in enumerate(tests):
        if test.contrast.shape[1] == 1:
            p[:, t] = one_df_p(values @ test.contrast[:, 0])
            continue
        for s, sample in enumerate(values):
            if test.kind == "effect":
                table = anova_table(sample, levels, within)
                p[s, t] = float(table.loc[table["effect"] == test.name, "p_read"].iloc[0])
            else:
                cols = np.flatnonzero(np.abs(test.contrast).sum(axis=1) > 0)
                p[s, t] = float(anova_table(sample[:, cols], [test.contrast.shape[1] + 1], [test.family])
                                ["p_read"].iloc[0])
    for family in {t.family for t in tests if t.kind == "simple"}:
        simple = [i for i, t in enumerate(tests) if t.kind == "simple" and t.family == family]
        p[:, simple] = holm_matrix(p[:, simple])
    return p


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--database-url", required=True)
    parser.add_argument("--study", required=True)
    parser.add_argument("--n", default="8,12,24,36")
    parser.add_argument("--simulations", type=int, default=1000)
    parser.add_argument("--reference-simulations", type=int, default=50)
    parser.add_argument("--jobs", type=int, default=1)
    args = parser.parse_args()
    from analysis.pipeline.analyze_study import DEFAULT_MEASURES, SUBJECT
    from analysis.pipeline.study_power import pilot_table, power_study
    from analysis.power_analysis.within_power import measure_data, measure_power, planned_tests, sample_pvalues

    ns = [int(x) for x in args.n.split(",")]
    with tempfile.TemporaryDirectory() as tmp:
        pilot, wall, cpu = timed(lambda: pilot_table(args.database_url, args.study, Path(tmp) / "prep"))
        kept, within, design, pilots = pilot.kept, pilot.within, pilot.design, pilot.pilots
        print(f"export and preparation: {wall:.1f} s wall, {cpu:.1f} s CPU ({pilots} pilot participants, "
              f"within {' × '.join(within)})")
        measures = [*DEFAULT_MEASURES, *(s.column for s in design.scales)]
        datas = [measure_data(kept, m, within, SUBJECT) for m in measures]
        _, wall, cpu = timed(lambda: [measure_power(d, ns, args.simulations, 0.05, np.random.default_rng(i))
                                      for i, d in enumerate(datas)])
        print(f"simulations ({len(datas)} measures × n {args.n} × {args.simulations}): {wall:.1f} s wall, "
              f"{cpu:.1f} s CPU")
        _, wall, cpu = timed(lambda: power_study(args.database_url, args.study, Path(tmp) / "all", ns,
                                                 simulations=args.simulations, jobs=args.jobs))
        print(f"power_study as steakhouse power runs it (--jobs {args.jobs}, plots): {wall:.1f} s wall, "
              f"{cpu:.1f} s CPU of this process")
        k = args.reference_simulations
        same, ref_cpu, new_cpu = True, 0.0, 0.0
        for i, data in enumerate(datas):
            counts = [len(lv) for lv in data.levels]
            tests = planned_tests(data.within, data.levels)
            for n in ns:
                sample = data.values[np.random.default_rng([i, n]).integers(len(data.values), size=(k, n))]
                ref, _, c_ref = timed(partial(reference_pvalues, sample, counts, data.within, tests))
                new, _, c_new = timed(partial(sample_pvalues, sample, tests))
                ref_cpu, new_cpu = ref_cpu + c_ref, new_cpu + c_new
                same &= bool(np.allclose(ref, new, rtol=1e-9, atol=1e-12, equal_nan=True))
        scale = args.simulations / k
        print(f"per-resample anova_table path: {ref_cpu:.2f} s CPU on {k} resamples per n, × {scale:g} = "
              f"{ref_cpu * scale:.0f} s CPU for {args.simulations}; vectorised on the same resamples: "
              f"{new_cpu:.3f} s CPU; same p values: {same}")


if __name__ == "__main__":
    main()
