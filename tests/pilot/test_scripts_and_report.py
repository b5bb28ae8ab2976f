"""The gaming scripts send what the browser sends (a held key: one press on the paper's clock, one per tick period
on the fixed clock; a random task only among the enabled buttons), and the pilot's report adds up who did the work
per robot × kitchen from the admin API's trials."""

from __future__ import annotations

from typing import Any

import numpy as np

from pilot.report import cell_reports, markdown
from pilot.scripts import Script
from server.game.needs import NEEDS, hands_fit

NEEDS_JSON = {s.value: need for s, need in NEEDS.items()}


def schedule(script: Script, mode: str, most: int = 6) -> list[float | None]:
    return [script.delay(mode, 5.0, sent) for sent in range(most)]


def test_a_held_key_is_one_press_on_the_papers_clock_and_repeats_each_tick_on_the_fixed_one():
    held = Script("hold_key")
    assert schedule(held, "wait_for_participant") == [0.0, None, None, None, None, None]
    assert schedule(held, "fixed_rate") == [0.0] + [0.2] * 5
    assert schedule(Script("tap_key", tap_seconds=0.25), "wait_for_participant") == [0.0] + [0.25] * 5
    assert schedule(Script("one_key"), "fixed_rate") == [0.0, None, None, None, None, None]
    assert schedule(Script("random_task", every_seconds=8), "wait_for_participant") == [0.0] + [8.0] * 5
    assert Script("hold_key").send(None, NEEDS_JSON, np.random.default_rng(0)) == {"type": "interrupt",
                                                                                   "action": "stay"}


def test_a_random_task_is_one_of_the_enabled_buttons():
    rng = np.random.default_rng(3)
    for held in (None, "meat", "clean_plate", "dish"):
        chosen = {Script("random_task").send(held, NEEDS_JSON, rng)["subtask"] for _ in range(200)}
        fitting = {s.value for s in NEEDS if hands_fit(s, held)}
        assert chosen == fitting, held


def trial(robot: str, kitchen: str, **values: Any) -> dict[str, Any]:
    row = {"kind": "main", "status": "finished", "robot": robot, "kitchen": kitchen, "recruit_id": "pilot-1-1",
           "delivered_by_participant": 1, "delivered_by_robot": 1, "task_steps": 10, "robot_task_steps": 30,
           "refused_steps": 2, "stand_ticks": 0, "think_seconds": 20.0, "selections": 10, "low_engagement": False,
           "invalid": False}
    return {**row, **values}


def test_the_report_adds_up_each_cell_of_the_runs_participants():
    rows = cell_reports([
        trial("fov_aware", "mid_2"), trial("fov_aware", "mid_2", delivered_by_participant=0, delivered_by_robot=2,
                                           low_engagement=True, invalid=True),
        trial("baseline", "mid_2", stand_ticks=3), trial("baseline", "mid_2", recruit_id="someone-else"),
        trial("baseline", "mid_2", kind="practice"), trial("baseline", "mid_2", status="running")],
        recruit_ids=["PILOT-1-1 "])
    assert [(r.robot, r.kitchen, r.trials) for r in rows] == [("baseline", "mid_2", 1), ("fov_aware", "mid_2", 2)]
    fov = rows[1]
    assert (fov.dishes_participant, fov.dishes_team, fov.dish_share) == (1, 4, 25.0)
    assert (fov.task_step_share, fov.low_engagement, fov.robot_invalid) == (25.0, 1, 0)
    table = markdown(rows, {"low_engagement": 1})
    assert "| fov_aware × mid_2 | 2 | 1 of 4 (25.0 %) | 20 of 80 (25.0 %) | 2.00 | 0 | 20.0 s (2.0 s) |" in table
    assert "| all × all | 3 | 2 of 6 (33.3 %) |" in table and "| baseline × mid_2 | 1 |" in table
    assert table.endswith("Participants screened out: 1 low engagement.")
