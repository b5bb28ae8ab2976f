"""Who does the work (:mod:`planner.work_share`; docs/domain.md §6, "Who does the work"): deliveries and task steps
per agent, the presses apart, the first delivery and the steps up to it."""

from __future__ import annotations

from planner.events import Event, EventKind
from planner.layout_gen import generate_named
from planner.planner_config import PlannerConfig
from planner.play import run_trial
from planner.robots import make_robot
from planner.rules import Rules
from planner.work_share import Tally, WorkShare


def test_each_agents_steps_presses_and_deliveries_are_counted_apart():
    steps = [
        (Event("human", EventKind.DISPENSE, (1, 1), "onion"), Event("robot", EventKind.BLOCKED, (2, 2))),
        (Event("human", EventKind.LOAD_BOARD, (3, 0), "onion"), Event("robot", EventKind.DISPENSE, (0, 2), "meat")),
        (Event("human", EventKind.CHOP, (3, 0), "onion"),),
        (Event("robot", EventKind.DELIVER, (6, 0), "dish"),),
        (Event("human", EventKind.DELIVER, (6, 0), "dish"),),
    ]
    work = WorkShare()
    for events in steps:
        work = work.observe(events)
    assert work.steps == Tally(person=3, robot=2), "a blocked move is no step; a chop is a press"
    assert work.presses == Tally(person=1, robot=0)
    assert work.deliveries == Tally(person=1, robot=1)
    assert work.first == Tally(person=0, robot=1), "the robot delivered the first dish"
    assert work.steps_to_first == Tally(person=2, robot=2), "the steps up to and with the first delivery"
    assert work.deliveries.person_share == 0.5 and Tally().person_share is None


def test_a_trials_work_adds_up_to_its_deliveries():
    rules = Rules()
    layout = generate_named(3)
    result = run_trial(layout, 0, robot=make_robot("fov_aware", layout, rules, PlannerConfig()))
    work = result.work
    assert result.finished and work.deliveries.total == rules.orders == result.delivered
    assert work.first.total == 1 and work.steps.total >= work.steps_to_first.total > 0
    assert (work + work).deliveries == Tally(2 * work.deliveries.person, 2 * work.deliveries.robot)
