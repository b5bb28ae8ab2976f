"""``steakhouse simulate``: the paper's simulation experiment writes trials.csv and prints the paired table."""

from __future__ import annotations

import csv

import pytest

from planner.experiment import COLUMNS
from server.cli import main


@pytest.mark.parametrize("lookahead", ["rollout", "abstract"])
def test_simulate_writes_paired_trials_and_the_table(lookahead, tmp_path, capsys):
    argv = ["simulate", "--layouts", "practice", "--robots", "fov_aware,baseline", "--seeds", "2",
            "--jobs", "1", "--quiet", "--lookahead", lookahead, "--out", str(tmp_path)]
    assert main(argv) == 0
    out = capsys.readouterr().out
    with (tmp_path / "trials.csv").open() as handle:
        reader = csv.DictReader(handle)
        rows = list(reader)
    assert tuple(reader.fieldnames or ()) == COLUMNS
    assert sorted((r["robot"], r["seed"]) for r in rows) == [
        ("baseline", "0"), ("baseline", "1"), ("fov_aware", "0"), ("fov_aware", "1")]
    assert all(r["finished"] == "1" and int(r["ticks"]) > 0 for r in rows)
    assert f"lookahead: {lookahead}" in out and "fov_aware vs baseline over 2 paired trials" in out


def test_an_unknown_lookahead_is_a_usage_error(tmp_path, capsys):
    with pytest.raises(SystemExit) as exit_info:
        main(["simulate", "--lookahead", "mcts", "--out", str(tmp_path)])
    assert exit_info.value.code == 2 and "invalid choice" in capsys.readouterr().err
