"""``steakhouse simulate``: the paper's simulation experiment writes trials.csv and prints the paired table and, with
three seeds or more, the paper's test of the KB gap with the seeds as participants; and the paper's robot behaviours
per kitchen and robot."""

from __future__ import annotations

import csv

import pytest

from planner.experiment import COLUMNS
from server.cli import main


# The abstract lookahead is several times slower than the rollouts; each planner's abstract trial of the practice
# kitchen is played to the end in tests/planner/test_reference.py, so here one seed shows the option reaches the
# trials, and the paired table (the same code for either lookahead) is read from the three seeds of the rollouts.
@pytest.mark.parametrize(("lookahead", "seeds"), [("rollout", 3), ("abstract", 1)])
def test_simulate_writes_paired_trials_and_the_table(lookahead, seeds, tmp_path, capsys):
    argv = ["simulate", "--layouts", "practice", "--robots", "fov_aware,baseline", "--seeds", str(seeds),
            "--jobs", "1", "--quiet", "--lookahead", lookahead, "--out", str(tmp_path)]
    assert main(argv) == 0
    out = capsys.readouterr().out
    with (tmp_path / "trials.csv").open() as handle:
        reader = csv.DictReader(handle)
        rows = list(reader)
    assert tuple(reader.fieldnames or ()) == COLUMNS
    assert sorted((r["robot"], r["seed"]) for r in rows) == [
        (robot, str(seed)) for robot in ("baseline", "fov_aware") for seed in range(seeds)]
    assert all(r["finished"] == "1" and int(r["ticks"]) > 0 for r in rows)
    for row in rows:  # the robot gap's parts add up to it (up to the rounding of each)
        parts = sum(float(row[f"gap_{part}_pct"]) for part in ("lag", "unseen", "stale"))
        assert parts == pytest.approx(float(row["robot_gap_pct"]), abs=0.02)
        assert 0 <= int(row["shown"]) <= int(row["holdings"]) and int(row["holdings"]) > 0
    assert "the paper's robot behaviours" in out
    for robot in ("fov_aware", "baseline"):
        mine = [r for r in rows if r["robot"] == robot]
        holdings = sum(int(r["holdings"]) for r in mine)
        shown = sum(int(r["shown"]) for r in mine) / holdings
        assert any(line.startswith(f"practice  {robot}") and f"{shown:.2f} ({holdings})" in line
                   for line in out.splitlines())
    assert f"lookahead: {lookahead}" in out and f"wrote {tmp_path / 'trials.csv'} ({2 * seeds} trials)" in out
    if seeds > 1:
        assert f"fov_aware vs baseline over {seeds} paired trials" in out
        assert f"kb_gap_mean, {seeds} seeds as participants (repeated-measures ANOVA):" in out
        assert f"  robot: F(1, {seeds - 1}) = " in out
    else:
        assert "seeds as participants" not in out


def test_an_unknown_lookahead_is_a_usage_error(tmp_path, capsys):
    with pytest.raises(SystemExit) as exit_info:
        main(["simulate", "--lookahead", "mcts", "--out", str(tmp_path)])
    assert exit_info.value.code == 2 and "invalid choice" in capsys.readouterr().err
