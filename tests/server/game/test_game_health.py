"""Robot health: the share of missed decisions and the moment it makes a trial invalid."""

from __future__ import annotations

from dataclasses import replace

from planner.geometry import Action, Direction
from planner.layout import parse_layout
from planner.objects import CLEAN_PLATE
from planner.rules import Rules
from planner.state import AgentState, initial_state
from planner.step import step
from server.game.health import RobotHealth
from study_config.study.validity import DEFAULT_MAX_MISSED_DECISIONS_PCT, Validity

RULES = Rules()


def run(health: RobotHealth, misses: list[bool]) -> list[RobotHealth]:
    seen = []
    for missed in misses:
        health = health.record(missed)
        seen.append(health)
    return seen


def test_the_study_default_is_five_percent():
    assert Validity().max_missed_decisions_pct == DEFAULT_MAX_MISSED_DECISIONS_PCT == 5.0


def test_a_trial_is_invalid_the_moment_its_final_share_is_certain_to_pass_the_threshold():
    # horizon 100 at 5 %: the 6th miss makes 6 of at most 100 decisions, whatever comes after.
    seen = run(RobotHealth(5.0, 100), [True] * 6)
    assert [h.invalid for h in seen] == [False] * 5 + [True]
    assert seen[-1].invalid_reason == "robot decisions missed their deadline: 6 of 6 (100.0 % > 5 %)"


def test_early_misses_that_the_rest_of_the_trial_dilutes_leave_it_valid():
    final = run(RobotHealth(5.0, 100), [True] * 5 + [False] * 95)[-1].final()
    assert not final.invalid and final.missed_pct == 5.0


def test_a_trial_that_ends_early_is_judged_on_the_decisions_it_made():
    health = run(RobotHealth(5.0, 400), [True] * 3 + [False] * 37)[-1]
    assert not health.invalid
    final = health.final()
    assert final.invalid and final.invalid_reason == "robot decisions missed their deadline: 3 of 40 (7.5 % > 5 %)"


def test_an_invalid_trial_stays_invalid_and_its_reason_carries_the_final_counts():
    seen = run(RobotHealth(5.0, 10), [True, False, False])
    assert seen[0].invalid and seen[-1].invalid
    final = seen[-1].final()
    assert final.invalid_reason == "robot decisions missed their deadline: 1 of 3 (33.3 % > 5 %)"


def test_a_healthy_trial_reports_its_share():
    final = run(RobotHealth(5.0, 50), [False] * 50)[-1].final()
    assert final.to_dict() == {"decisions": 50, "missed": 0, "failed": 0, "missed_pct": 0.0, "threshold_pct": 5.0,
                               "flickers": 0, "max_flickers": 0, "invalid": False, "invalid_reason": None}


def test_failed_decisions_count_with_the_late_ones_and_are_named():
    health = RobotHealth(threshold_pct=5.0, horizon=40)
    for failed in (True, True):
        health = health.record(False, failed)
    health = health.record(True)
    assert (health.missed, health.failed, health.lost) == (1, 2, 3)
    assert health.invalid and health.invalid_reason == (
        "robot decisions missed their deadline or failed: 1 missed and 2 failed of 3 (100.0 % > 5 %)")


KITCHEN = parse_layout("XXXXXXX\nO  1 2M\nX     D\nXPBWSXX\n", name="flicker")
"""The robot at (3, 1) faces north, the counter (3, 0)."""


def _flicker(health: RobotHealth) -> RobotHealth:
    """The robot puts a clean plate down on the counter it faces and picks it up again, nothing else changing."""
    start = initial_state(KITCHEN, RULES)
    world = replace(start, robot=AgentState((3, 1), Direction.NORTH, CLEAN_PLATE))
    for _ in range(2):
        after, events = step(KITCHEN, world, {"robot": Action.INTERACT, "human": Action.STAY}, RULES)
        health, world = health.stepped(world, events, RULES), after
    return health


def test_a_robot_that_undoes_its_last_interaction_makes_the_trial_invalid_and_the_reason_stays():
    health = _flicker(RobotHealth(5.0, 100))
    assert health.flickers == 1 and health.invalid
    assert health.invalid_reason == "the robot undid its own last interaction 1 times with nothing else changed (> 0)"
    final = run(health, [False] * 10)[-1].final()
    assert final.invalid_reason == health.invalid_reason, "a healthy share of decisions does not clear a flicker"
    assert Validity().max_robot_flickers == 0


def test_a_study_may_allow_some_flickers():
    health = _flicker(RobotHealth(5.0, 100, max_flickers=1))
    assert health.flickers == 1 and not health.invalid
