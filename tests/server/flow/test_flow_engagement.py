"""Engagement and standing rules: a round without the participant's actions, or with the cook idle
past the study's share, is low-engagement; abandoned and low-engagement rounds beyond the allowance screen out,
robot-invalid ones never do; a refused device stops a participant counting until an accepted one."""

from __future__ import annotations

from dataclasses import replace
from types import SimpleNamespace

import pytest

from server.flow.engagement import engagement_problem
from server.flow.standing import not_taking_part, review_device, round_problem
from store.activity import Activity
from store.tables import ParticipantRow
from study_config.study.validity import Validity

PLAYED = Activity(selections=12, interrupts=3, key_actions=2, ticks=120, idle_ticks=10, waited_seconds=0.0,
                  refused_steps=1, delivered_by_participant=1, delivered_by_robot=1, tick_rate_hz=5.0, task_steps=20,
                  robot_task_steps=25)


def test_a_round_with_no_actions_or_an_idle_cook_is_low_engagement():
    rules = Validity()
    assert engagement_problem(PLAYED, rules) is None
    idle = replace(PLAYED, selections=0, interrupts=0, idle_ticks=120)
    assert str(engagement_problem(idle, rules)) == "low_engagement: 0 participant action(s), fewer than 1"
    # Under the waiting clock the idle share is the waited time at the tick rate: 200 s at 5 Hz = 1000 periods.
    waited = replace(PLAYED, idle_ticks=0, waited_seconds=200.0)
    assert waited.idle_pct == pytest.approx(100 * 1000 / 1120)
    assert engagement_problem(waited, rules) is None, "89.3 % is within the default 95 %"
    assert str(engagement_problem(waited, Validity(max_idle_pct=80))) == ("low_engagement: the cook was idle 89.3 % of "
                                                                     "the round, more than 80 %")
    assert engagement_problem(PLAYED, Validity(min_participant_actions=16)) is not None
    assert replace(PLAYED, ticks=0, idle_ticks=0).idle_pct is None


def trial(index: int, status: str = "finished", engagement: str | None = None, invalid: str | None = None):
    return SimpleNamespace(index=index, status=status, end_reason="grace_expired" if status == "abandoned"
                           else "delivered", engagement_reason=engagement, invalid_reason=invalid)


def test_rounds_the_participant_did_not_take_part_in_screen_out_beyond_the_allowance():
    rules = Validity()
    played = [trial(0), trial(1)]
    assert not_taking_part(played, rules) is None and round_problem(played[0]) is None
    assert not_taking_part([trial(0, "abandoned"), trial(1)], rules) == "abandoned_rounds"
    assert not_taking_part([trial(0), trial(1, engagement="low_engagement: x")], rules) == "low_engagement"
    assert not_taking_part([trial(0, engagement="low_engagement: x")], Validity(max_invalid_rounds=1)) is None
    robot = trial(0, invalid="robot decisions missed their deadline")
    assert not_taking_part([robot], rules) is None, "the robot's failure is not the participant's"
    assert round_problem(robot) == "main round 1 robot-invalid: robot decisions missed their deadline"
    both = trial(0, engagement="low_engagement: 30.0 % refused", invalid="robot decisions missed their deadline")
    assert not_taking_part([both], rules) is None, "a round the robot broke says nothing of the participant"
    assert round_problem(both) == "main round 1 robot-invalid: robot decisions missed their deadline"


def test_a_refused_device_stops_counting_until_an_accepted_one():
    row = ParticipantRow(uncounted_reason=None)
    review_device(row, ["small_screen"])
    assert row.uncounted_reason == "device_refused: small_screen"
    review_device(row, [])
    assert row.uncounted_reason is None
    row.uncounted_reason = "main round 1 abandoned (grace_expired)"
    review_device(row, [])
    assert row.uncounted_reason == "main round 1 abandoned (grace_expired)", "a round's reason stays"


def test_a_round_left_to_the_robot_or_chosen_blindly_is_low_engagement_with_its_rule():
    rules = Validity(min_task_step_pct=10, max_refused_task_pct=30)
    played = replace(PLAYED, task_steps=20, robot_task_steps=20, refused_steps=2)
    assert engagement_problem(played, rules) is None
    tapped = replace(PLAYED, selections=0, interrupts=150, key_actions=150, task_steps=0, robot_task_steps=28)
    problem = engagement_problem(tapped, rules)
    assert problem is not None and (problem.rule, problem.value, problem.limit) == ("task_steps", 0.0, 10)
    assert str(problem) == "low_engagement: the participant made 0.0 % of the team's task steps, fewer than 10 %"
    blind = replace(played, selections=30, refused_steps=12)
    problem = engagement_problem(blind, rules)
    assert problem is not None and (problem.rule, problem.value) == ("refused_tasks", 40.0)
    reason = "low_engagement: 40.0 % of the participant's task choices so far were refused, more than 30 %"
    assert problem.to_dict() == {"reason": reason, "rule": "refused_tasks", "value": 40.0, "limit": 30}
    few = replace(played, selections=6, refused_steps=4)
    assert engagement_problem(few, rules) is None, "four refusals are too few to judge a share by"
    # Pooled with the earlier rounds: one unlucky round among careful ones passes, a habit does not.
    unlucky = replace(played, selections=20, refused_steps=8)
    assert engagement_problem(unlucky, rules) is not None
    assert engagement_problem(unlucky, rules, earlier=(60, 4)) is None
    assert engagement_problem(unlucky, rules, earlier=(60, 20)) is not None
    assert engagement_problem(tapped, Validity(min_task_step_pct=0)) is None, "0 turns the rule off"
    nobody = replace(PLAYED, task_steps=0, robot_task_steps=0)
    assert engagement_problem(nobody, rules) is None, "a round nobody could work in says nothing of the share"
    short = replace(PLAYED, task_steps=0, robot_task_steps=9)
    assert engagement_problem(short, rules) is None, "nor does one too short for the team to make ten steps"
