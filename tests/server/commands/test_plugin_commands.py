"""A plug-in robot in the commands and benchmarks the shipped robots play in: ``steakhouse robots`` lists it with
its package and version, ``simulate`` and the behaviour and no-stall benchmarks play it (guarded: a robot that
raises, answers illegally or hangs flags its trials and the run exits 1), ``pilot`` runs simulated participants
with it through the server."""

from __future__ import annotations

import asyncio
import csv
import importlib
import sys
from pathlib import Path

from planner.experiment import TrialSpec, run_spec
from planner.robot_guard import HANG_S
from server.cli import main
from study_config import load_layout

REPO = Path(__file__).resolve().parents[3]


def test_robots_lists_every_installed_robot_with_its_package_and_version(capsys, example_robots, broken_robots):
    assert main(["robots"]) == 1, "a robot that cannot be used is there"
    lines = {line.split()[0]: line for line in capsys.readouterr().out.splitlines()}
    assert lines["fov_aware"].split()[1:4] == ["steakhouse-study", lines["fov_aware"].split()[2], "planner.robots"]
    assert lines["mylab_scripted"].split()[1:5] == ["mylab-robots", "0.1.0", "mylab_robots.scripted:PLUGIN", "ok"]
    assert "cannot be used: cannot be imported: ModuleNotFoundError" in lines["broken_import"]
    assert main(["robots", "--settings", "mylab_scripted"]) == 0
    out = capsys.readouterr().out
    assert "  first: Literal['meat', 'onion', 'plate'] = 'meat'" in out
    assert "  patience: int = 6" in out


def test_simulate_plays_the_example_robots(tmp_path, capsys, example_robots):
    argv = ["simulate", "--layouts", "practice", "--robots", "mylab_scripted,mylab_learned,baseline", "--seeds", "2",
            "--jobs", "1", "--quiet", "--out", str(tmp_path)]
    assert main(argv) == 0
    with (tmp_path / "trials.csv").open() as handle:
        rows = list(csv.DictReader(handle))
    assert sorted({r["robot"] for r in rows}) == ["baseline", "mylab_learned", "mylab_scripted"]
    assert all(r["finished"] == "1" and r["robot_faults"] == "0" for r in rows)
    assert "flagged" not in capsys.readouterr().out


def test_simulate_flags_the_trials_of_a_robot_that_fails_and_exits_1(tmp_path, capsys, broken_robots):
    argv = ["simulate", "--layouts", "practice", "--robots", "broken_raises,broken_illegal", "--seeds", "1",
            "--jobs", "1", "--quiet", "--out", str(tmp_path)]
    assert main(argv) == 1
    out = capsys.readouterr().out
    assert "2 trial(s) flagged: the robot failed" in out
    assert "broken_raises on practice seed 0: " in out and "first at tick 2: raised RuntimeError: the lab's planner " \
                                                          "has a bug" in out
    assert "first at tick 2: illegal decision: answered the action 'fly'" in out
    assert main(["simulate", "--robots", "broken_import", "--out", str(tmp_path)]) == 2
    assert "cannot be imported: ModuleNotFoundError" in capsys.readouterr().err


def test_a_headless_decision_that_hangs_is_stopped_and_flags_its_trial(broken_robots):
    assert HANG_S >= 5, "shipped robots decide in milliseconds; a hang is generous"
    row = run_spec(TrialSpec(load_layout("practice"), "broken_hangs", 0, hang_s=0.3))
    assert row["robot_faults"] == int(str(row["ticks"])) - 2 and str(row["robot_fault"]).startswith(
        "tick 2: hung: the decision was still running after 0.3 s and was stopped")


def test_the_behaviour_and_no_stall_benchmarks_play_a_plug_in(tmp_path, capsys, example_robots, broken_robots):
    sys.path.insert(0, str(REPO / "benchmarks" / "planner"))
    behaviours = importlib.import_module("behaviours")
    no_stall = importlib.import_module("no_stall")
    assert behaviours.main(["--shipped", "practice", "--seeds", "1", "--robots", "mylab_learned,baseline",
                            "--jobs", "1", "--out", str(tmp_path / "b")]) == 0
    assert "mylab_learned" in capsys.readouterr().out
    assert no_stall.main(["--shipped", "practice", "--generator-seeds", "none", "--seeds", "1", "--robots",
                          "mylab_scripted", "--partners", "simulated,still", "--jobs", "1"]) == 0
    assert "mylab_scripted" in capsys.readouterr().out
    assert behaviours.main(["--shipped", "practice", "--seeds", "1", "--robots", "broken_raises", "--jobs", "1",
                            "--out", str(tmp_path / "broken")]) == 1
    assert "1 trial(s) flagged" in capsys.readouterr().out


def test_pilot_runs_simulated_participants_with_the_example_robots(live_server, study_file, example_robots):
    from pilot.client import Seat
    from pilot.config import ParticipantConfig
    from pilot.run import run_pilot
    from store.tables import TrialRow
    from study_config.catalog import load_one

    path = study_file(kitchens=["practice"], robots=["mylab_scripted", "mylab_learned"],
                      world={"orders": 1, "horizon": 80, "kb_delay": 1}, timing={"tick_rate_hz": 5})
    server = live_server([path], robot_workers=1)
    seat = Seat(server.url, "admin-secret", load_one(path), ParticipantConfig())
    result = asyncio.run(run_pilot(seat, 2, 2, seed=3))
    assert not result.failures and all(o.completed for o in result.outcomes)
    with server.services.store.transaction() as session:
        rows = session.query(TrialRow).all()
    assert sorted({(r.robot, r.robot_package) for r in rows}) == [("mylab_learned", "mylab-robots"),
                                                                  ("mylab_scripted", "mylab-robots")]
    assert all(r.status == "finished" and r.failed_decisions == 0 for r in rows)
