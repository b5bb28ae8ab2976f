"""The reader of the reference's VR study logs (benchmarks/planner/vr_logs.py) on a hand-made log in their
shape: two decision steps of a pickup and a dish delivery, the person's heading from the headset yaw."""

from __future__ import annotations

import importlib.util
import json
import math
import sys
from pathlib import Path
from typing import Any

import pytest

REPO = Path(__file__).resolve().parents[2]
spec = importlib.util.spec_from_file_location("vr_logs", REPO / "benchmarks" / "planner" / "vr_logs.py")
assert spec is not None and spec.loader is not None
vr_logs = importlib.util.module_from_spec(spec)
sys.modules["vr_logs"] = vr_logs
spec.loader.exec_module(vr_logs)


def step(robot_xy, robot_held, person_xy, yaw, orders=2):
    """One decision step: the state sent (reference grid) and two headset samples (``[y − 1, x − 1, letter]``)."""
    held = None if robot_held is None else {"id": 1, "name": robot_held, "position": robot_xy, "state": None}
    sample = {"robot_ml": [robot_xy[1] - 1, robot_xy[0] - 1, "N"],
              "human_ml": [person_xy[1] - 1, person_xy[0] - 1, "S"], "human_ll_ori": [0.0, 0.0, yaw]}
    return {"overcooked_state_sent": {"players": [{"position": robot_xy, "orientation": [0, 1], "held_object": held},
                                                  {"position": person_xy, "orientation": [0, 1], "held_object": None}],
                                      "objects": [], "order_list": ["steak"] * orders},
            "low_level_logs": [sample, sample]}


SOUTH, NORTH = 0.0, math.pi


def log(person_yaw: float) -> dict[str, Any]:
    """The robot picks up a dish below the person and holds it three steps, then delivers it."""
    steps = [step([5, 3], None, [5, 1], person_yaw)] + [step([5, 3], "dish", [5, 1], person_yaw)] * 3 + \
        [step([5, 3], None, [5, 1], person_yaw, orders=1)]
    return {"i": len(steps) + 1, "event_start_time": 0.0, "log_id": 1, "0": {"low_level_logs": []},
            **{str(k + 1): s for k, s in enumerate(steps)}}


def test_the_yaw_gives_the_heading_in_grid_axes():
    assert vr_logs.heading_of(SOUTH) == pytest.approx((0.0, 1.0))
    assert vr_logs.heading_of(math.pi / 2) == pytest.approx((1.0, 0.0))


def test_a_robot_the_person_faces_is_seen_and_its_dish_trip_counts():
    frames = vr_logs.frames_of(log(SOUTH), "mid", 120.0)
    assert [f.held for f in frames] == [None, "dish", "dish", "dish", None]
    assert [f.seen for f in frames] == [True] * 5
    assert frames[-1].delivered
    b = vr_logs.measure(frames, 3)
    assert (b.holdings, b.shown, b.trips, b.trip_share) == (1, 1, 1, 1.0)


def test_the_same_robot_behind_the_person_is_not_seen():
    b = vr_logs.measure(vr_logs.frames_of(log(NORTH), "mid", 150.0), 3)
    assert (b.holdings, b.shown, b.trips, b.trip_share) == (1, 0, 1, 0.0)


def test_only_the_study_logs_of_counted_participants_are_read():
    names = ["8/8_none_aware.json", "8/8_mid_unaware.json", "10/10_mid_unaware_short.json", "11/11_none_aware.json",
             "18/18_mid_1_aware.json", "2/steak_none_3_log_dict.json", "11/notes.txt"]
    found = vr_logs.log_files(names, include_ignored=False)
    assert [(f.participant, f.kitchen, f.robot) for f in found] == [(8, "mid", "unaware"), (8, "none", "aware")]
    assert len(vr_logs.log_files(names, include_ignored=True)) == 3


def test_a_log_without_its_step_count_is_a_clear_error():
    with pytest.raises(vr_logs.LogError, match="'i'"):
        vr_logs.frames_of({"1": {}}, "none", 120.0)


def test_a_missing_reference_is_a_usage_error(tmp_path, capsys):
    with pytest.raises(SystemExit) as exit_info:
        vr_logs.main([str(tmp_path)])
    assert exit_info.value.code == 2
    assert "neither a bare git directory" in capsys.readouterr().err


def test_it_reads_a_checked_out_folder(tmp_path, capsys):
    folder = tmp_path / vr_logs.LOG_DIR / "8"
    folder.mkdir(parents=True)
    (folder / "8_mid_aware.json").write_text(json.dumps(log(SOUTH)))
    assert vr_logs.main([str(tmp_path), "--angles", "120"]) == 0
    out = capsys.readouterr().out
    assert "mid_2" in out and "1.00 (1)" in out and "1.00 (1 trips)" in out


def test_who_did_the_work_is_read_from_the_agents_hands():
    """The robot takes the dish and delivers it (two steps of its own, one delivery, the first); the person, who
    takes an onion between, one step."""
    steps = [step([5, 3], None, [5, 1], SOUTH), step([5, 3], "dish", [5, 1], SOUTH)]
    onion = step([5, 3], "dish", [5, 1], SOUTH)
    onion["overcooked_state_sent"]["players"][1]["held_object"] = {"id": 2, "name": "onion", "position": [5, 1]}
    steps += [onion, step([5, 3], None, [5, 1], SOUTH, orders=1)]
    steps[-1]["overcooked_state_sent"]["players"][1]["held_object"] = {"id": 2, "name": "onion", "position": [5, 1]}
    work = vr_logs.work_of({"i": len(steps) + 1, **{str(k + 1): s for k, s in enumerate(steps)}})
    assert (work.steps.robot, work.steps.person) == (2, 1)
    assert (work.deliveries.robot, work.deliveries.person, work.first.robot) == (1, 0, 1)
    assert work.steps_to_first == work.steps and work.presses.total == 0
