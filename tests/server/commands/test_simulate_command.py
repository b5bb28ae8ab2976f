"""``steakhouse simulate``: the paper's simulation experiment writes trials.csv and prints the paired table and, with
three seeds or more, the paper's test of the KB gap with the seeds as participants; and the paper's robot behaviours
per kitchen and robot."""

from __future__ import annotations

import csv

import pytest

from planner.experiment import COLUMNS, TrialSpec, run_spec
from planner.rules import Rules
from server.cli import main
from study_config import load_layout


@pytest.mark.parametrize("seeds", [3, 1])
def test_simulate_writes_paired_trials_and_the_table(seeds, tmp_path, capsys):
    argv = ["simulate", "--layouts", "practice", "--robots", "fov_aware,baseline", "--seeds", str(seeds),
            "--jobs", "1", "--quiet", "--out", str(tmp_path)]
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
    assert f"wrote {tmp_path / 'trials.csv'} ({2 * seeds} trials)" in out
    if seeds > 1:
        assert f"fov_aware vs baseline over {seeds} paired trials" in out
        assert f"kb_gap_mean, {seeds} seeds as participants (repeated-measures ANOVA):" in out
        assert f"  robot: F(1, {seeds - 1}) = " in out
    else:
        assert "seeds as participants" not in out


def test_an_unknown_option_is_a_usage_error(tmp_path, capsys):
    """The abstract lookahead (``--lookahead``) is gone with the code only it reached (docs/changes.md)."""
    with pytest.raises(SystemExit) as exit_info:
        main(["simulate", "--lookahead", "abstract", "--out", str(tmp_path)])
    assert exit_info.value.code == 2 and "unrecognized arguments: --lookahead" in capsys.readouterr().err


STUDY = """\
id: rehearse
title: Rehearse a variant
kitchens: [practice]
robots: [baseline, patient]
factors: [robot]
robot_variants:
  patient: {planner: baseline, settings: {standoff_ticks: 40, stall_ticks: 90}}
world: {orders: 1, kb_delay: 2, fov_angle: 90, delivery_reward: 7}
"""


def test_simulate_a_study_plays_its_kitchens_robots_and_world(tmp_path, capsys):
    study = tmp_path / "rehearse.yaml"
    study.write_text(STUDY, encoding="utf-8")
    out_dir = tmp_path / "out"
    assert main(["simulate", "--study", str(study), "--seeds", "3", "--jobs", "1", "--quiet",
                 "--out", str(out_dir)]) == 0
    out = capsys.readouterr().out
    with (out_dir / "trials.csv").open() as handle:
        rows = list(csv.DictReader(handle))
    assert sorted((r["layout"], r["robot"]) for r in rows) == [("practice", "baseline")] * 3 + [
        ("practice", "patient")] * 3
    assert all(r["finished"] == "1" and r["reward"] == "7" for r in rows), "one order of the study's world"
    # The variant is the baseline planner with its settings, the person at the study's view and KB delay.
    rules = Rules(orders=1, delivery_reward=7)
    expected = [run_spec(TrialSpec(load_layout("practice"), "patient", seed, 90.0, 2, planner="baseline",
                                   settings=(("standoff_ticks", 40), ("stall_ticks", 90)), rules=rules))
                for seed in range(3)]
    timed = {"decision_ms_p50", "decision_ms_p99"}
    assert [{k: v for k, v in r.items() if k not in timed} for r in rows if r["robot"] == "patient"] == [
        {k: str(v) for k, v in row.items() if k not in timed} for row in expected]
    assert "kb_gap_mean, 3 seeds as participants" in out and "practice  patient" in out


def test_a_variant_s_settings_change_only_that_robot_s_setup():
    spec = TrialSpec(load_layout("practice"), "patient", 0, 90.0, 2, planner="baseline",
                     settings=(("standoff_ticks", 40),))
    setup = spec.setup()
    assert dict(setup.settings)["standoff_ticks"] == 40
    assert (setup.person.fov_angle, setup.person.kb_delay) == (90.0, 2)
    assert "standoff_ticks" not in dict(TrialSpec(load_layout("practice"), "baseline", 0).setup().settings)


def test_simulate_a_study_says_what_it_cannot_take(tmp_path, capsys):
    study = tmp_path / "rehearse.yaml"
    study.write_text(STUDY, encoding="utf-8")
    angles = tmp_path / "angles.yaml"
    angles.write_text(STUDY.replace("fov_angle: 90, ", "") + "fov_angles: [90, 150]\nbetween: [fov_angle]\n",
                      encoding="utf-8")
    bad = tmp_path / "bad.yaml"
    bad.write_text(STUDY.replace("standoff_ticks: 40", "standoff_ticks: -1"), encoding="utf-8")
    for argv, reason in [
        (["--study", str(study), "--robots", "baseline"], "--study gives the kitchens, robots and KB delay; "
                                                          "leave out --robots"),
        (["--study", str(angles)], "the study has 2 fields of view (90, 150): choose one with --human-angle"),
        (["--study", str(bad)], "robot_variants.patient.settings.standoff_ticks: must be 0 or more"),
    ]:
        assert main(["simulate", *argv, "--out", str(tmp_path / "x")]) == 2
        assert reason in capsys.readouterr().err
    assert not (tmp_path / "x").exists(), "nothing is simulated"
