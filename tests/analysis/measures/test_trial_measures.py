"""Per-trial measures of a hand-made tiny trial stored on SQLite and PostgreSQL: known ticks and events
give known KB gap, interrupts per selection, switches, redundant actions, work shares and robot timing."""

from __future__ import annotations

import math
from typing import Any

import pytest
from sqlalchemy import create_engine
from steakhouse_store_study import hand_trial, join

from analysis.measures.trial_measures import TRIAL_MEASURES, trial_measures
from analysis.source.store_reader import StoredTrial, read_events, read_study, read_ticks


def agent(pos: tuple[int, int], facing: str, held: str | None = None) -> dict[str, Any]:
    return {"pos": list(pos), "facing": facing, "held": held}


def world(tick: int, human: dict[str, Any], robot: dict[str, Any], grill: int | None,
          objects: list[dict[str, Any]] | None = None) -> dict[str, Any]:
    return {"human": human, "robot": robot, "objects": objects or [], "grills": [grill], "boards": [None],
            "sinks": [None], "orders_left": 1, "tick": tick, "score": 0}


INITIAL = world(0, agent((7, 5), "east"), agent((7, 4), "east", "meat"), None)
# tick: (gap grill, board, sink, robot_held), robot in FOV, subtask, controller subtask after, lateness, decision
# ms, missed, world after the step.
SCRIPT = [
    ((0, 0, 0, 0), True, "pickup_meat", "pickup_meat", 2.0, 10.0, False,
     world(1, agent((7, 5), "east"), agent((7, 4), "east"), 1)),                      # the robot loads the grill
    ((1, 0, 0, 1), False, "pickup_meat", "pickup_meat", 4.0, 20.0, False,
     world(2, agent((7, 5), "east", "meat"), agent((7, 4), "east"), 2)),              # redundant meat pickup
    ((1, 0, 0, 0), False, "pickup_onion", None, 6.0, 30.0, False,                      # switch meat → onion
     world(3, agent((7, 5), "east", "meat"), agent((7, 4), "east"), 3)),
    ((0, 0, 0, 0), True, "pickup_plate", "pickup_plate", 100.0, 160.0, True,          # not a switch: onion done
     world(4, agent((7, 5), "east"), agent((7, 4), "east"), 4, [{"pos": [8, 5], "obj": "meat"}])),
]
def event(agent: str, kind: str) -> dict[str, Any]:
    return {"agent": agent, "kind": kind, "pos": [8, 4], "obj": None}


# The world events of each step: the robot does both prep steps, nobody plates, two steps have a collision.
WORLD_EVENTS = [[event("robot", "start_cooking")], [event("human", "dispense"), event("robot", "blocked")],
                [event("human", "blocked"), event("robot", "blocked")], [event("human", "put_down"),
                                                                         event("robot", "wash")]]
EVENTS = [(0, "select_subtask", {"subtask": "pickup_meat"}), (1, "interrupt", {"action": "up"}),
          (1, "interrupt", {"action": "stop"}), (2, "select_subtask", {"subtask": "pickup_onion"}),
          (3, "select_subtask", {"subtask": "pickup_plate"}), (3, "blur", {}), (3, "idle", {"idle_ms": 5000}),
          (3, "stall_hint", {"code": "holding", "text": "You are still holding the dirty plate."}),
          (3, "connect", {})]
EXPECTED = {
    "ticks": 4, "finished": 1, "delivered": 1, "score": 20,
    "kb_diff_freq": 50.0, "kb_diff_avg": 1.5, "kb_diff_mean": 0.75,
    "kb_gap_mean": 0.75, "kb_gap_ticks_pct": 50.0, "kb_gap_grill_pct": 50.0, "kb_gap_board_pct": 0.0,
    "kb_gap_sink_pct": 0.0, "kb_gap_robot_held_pct": 25.0,
    "interrupts": 2, "selections": 3, "interrupts_per_selection": 40.0,
    "robot_in_fov_pct": 50.0, "subtask_switches": 1, "redundant_actions": 1,
    "human_prep_pct": 0.0, "human_plating_pct": math.nan, "collisions": 2,
    "decision_ms_mean": 55.0, "decision_ms_p95": 30.0 + 0.85 * 130.0,
    "lateness_ms_mean": 28.0, "lateness_ms_p99": 6.0 + 0.97 * 94.0, "deadline_misses": 1,
    "disconnects": 0, "blurs": 1, "idle_events": 1, "errors": 0, "stall_hints": 1,
}


def tick_rows(with_reference: bool = True) -> list[dict[str, Any]]:
    """The scripted ticks. The modelled KB misses the steak on the grill and believes the robot holds meat where
    the script has a grill and a robot-held gap; the reference's gap is then the same as ours (1 each). Summaries
    ``with_reference`` carry the reference's state infos (the writer derives ``kb_diff`` from them); without,
    they are as stored before, and the reader computes the gap from the stored world and KB."""
    rows = []
    for n, (gap, in_fov, subtask, after, late, decision, missed, state) in enumerate(SCRIPT, 1):
        components = dict(zip(("grill", "board", "sink", "robot_held"), gap, strict=True))
        kb_robot = dict(state["robot"], held="meat" if gap[3] else state["robot"]["held"])
        kb_state = {"objects": [], "grills": [None if gap[0] else state["grills"][0]], "boards": [None],
                    "sinks": [None], "robot": kb_robot}
        kb_summary: dict[str, Any] = {"grill": ["empty"], "board": ["empty"], "sink": ["empty"], "robot_held": None}
        world_summary: dict[str, Any] = {"grill": ["cooking"], "board": ["empty"], "sink": ["empty"],
                                         "robot_held": None}
        if with_reference:
            kb_summary["reference"] = {"grill": 0 if gap[0] else 1, "board": -1, "sink": -1,
                                       "robot_held": kb_robot["held"]}
            world_summary["reference"] = {"grill": 1, "board": -1, "sink": -1, "robot_held": state["robot"]["held"]}
        rows.append({
            "tick": n, "human_action": "interact", "robot_action": "stay", "action_source": "subtask",
            "subtask": subtask, "kb_summary": kb_summary, "world_summary": world_summary,
            "kb_gap": components, "kb_gap_total": sum(gap), "robot_in_fov": in_fov, "lateness_ms": late,
            "decision_ms": decision, "robot_missed": missed, "robot_info": None, "world_state": state,
            "kb_state": kb_state, "controller": {"subtask": after, "last": subtask},
            "world_events": WORLD_EVENTS[n - 1],
        })
    return rows


@pytest.fixture(params=["reference", "older"])
def tiny(request, store, loaded_2x2) -> tuple[str, int]:
    """The tiny trial stored with the reference's gap (``ticks.kb_diff``), or as a version before it stored them."""
    participant = join(store, loaded_2x2, "tiny-1")
    trial_id = hand_trial(store, loaded_2x2, participant, INITIAL, tick_rows(request.param == "reference"), EVENTS)
    return str(store.url.render_as_string(hide_password=False)), trial_id


def test_measures_of_a_hand_made_trial_read_from_the_store(tiny) -> None:
    url, trial_id = tiny
    engine = create_engine(url)
    with engine.connect() as conn:
        data = read_study(conn, "two_by_two")
        [trial] = [t for t in data.trials if t.id == trial_id]
        measures = trial_measures(trial, read_ticks(conn, trial_id), read_events(conn, "two_by_two")[trial_id])
    engine.dispose()
    assert set(measures) == set(EXPECTED)
    for name, value in EXPECTED.items():
        assert measures[name] == pytest.approx(value, nan_ok=True), name


def test_interrupts_per_selection_is_empty_without_any_input() -> None:
    trial = StoredTrial(id=1, participant_id=1, kind="main", index=0, attempt=1, condition="stay@x", kitchen="x",
                        robot="stay", view="top_down", fov_angle=90.0,
                        seed=1, config_hash="h", status="finished", end_reason="horizon",
                        started_at=None, ended_at=None, ticks=0, delivered=0, score=0,  # type: ignore[arg-type]
                        initial_state=INITIAL)
    measures = trial_measures(trial, [], [])
    assert math.isnan(measures["interrupts_per_selection"]) and measures["interrupts"] == 0
    assert math.isnan(measures["kb_gap_mean"]) and math.isnan(measures["decision_ms_p95"])
    assert math.isnan(measures["kb_diff_freq"]) and math.isnan(measures["kb_diff_avg"])
    assert measures["finished"] == 0 and measures["ticks"] == 0
    assert set(TRIAL_MEASURES) <= set(measures)
