"""The generated-kitchen benchmark runs end to end on a tiny set and resumes from its CSV without redoing
finished trials (it had broken silently when ``TrialSpec`` began to carry the kitchen itself)."""

from __future__ import annotations

import csv
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


def test_the_generated_kitchen_table_runs_and_resumes(tmp_path):
    command = [sys.executable, str(REPO / "benchmarks" / "planner" / "generated.py"), "--generator-seeds", "1000",
               "--sim-seeds", "1", "--shipped-seeds", "0", "--jobs", "1", "--out", str(tmp_path)]
    first = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=REPO)
    assert first.returncode == 0, first.stderr
    with (tmp_path / "trials.csv").open(newline="") as handle:
        rows = list(csv.DictReader(handle))
    assert sorted(r["robot"] for r in rows) == ["baseline", "fov_aware"]
    assert {r["layout"] for r in rows} == {next((tmp_path / "kitchens").glob("*.layout")).stem}
    assert "generated" in first.stdout and "2 trials" in first.stdout

    again = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=REPO)
    assert again.returncode == 0, again.stderr
    with (tmp_path / "trials.csv").open(newline="") as handle:
        assert len(list(csv.DictReader(handle))) == 2


def test_a_csv_written_with_other_columns_is_refused_and_kept(tmp_path):
    old = "layout,robot,seed,ticks\ngen_1000,baseline,0,120\n"
    (tmp_path / "trials.csv").write_text(old)
    command = [sys.executable, str(REPO / "benchmarks" / "planner" / "generated.py"), "--generator-seeds", "1000",
               "--sim-seeds", "1", "--shipped-seeds", "0", "--jobs", "1", "--out", str(tmp_path)]
    refused = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=REPO)
    assert refused.returncode != 0 and "written with other columns" in refused.stderr
    assert (tmp_path / "trials.csv").read_text() == old
