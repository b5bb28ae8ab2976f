"""What a QMDP robot's subtasks are worth (:mod:`planner.valuation`): the rollouts of every likely subtask of the
person, weighted by the belief, on the decision's one seed; the ranking the robot chooses by; the deadline."""

from __future__ import annotations

import time

from planner.flicker import FlickerWatch
from planner.kb import initial_kb
from planner.moment import Moment
from planner.planner_config import PlannerConfig
from planner.rollout import RobotTasker
from planner.rules import Rules
from planner.state import initial_state
from planner.subtasks import Subtask
from planner.valuation import Valuation, Values
from study_config import load_layout

RULES = Rules()
LAYOUT = load_layout("none_3")
LIKELY = ((Subtask.PICKUP_MEAT, 0.5), (Subtask.PICKUP_ONION, 0.3), (Subtask.PICKUP_PLATE, 0.2))


def moment(seed: int = 11, deadline: float | None = None, current: Subtask | None = None) -> Moment:
    world = initial_state(LAYOUT, RULES)
    return Moment(world, initial_kb(world), LIKELY, seed, 42, 0, False, True, current, FlickerWatch(), deadline)


def test_a_subtasks_value_is_the_belief_weighted_rollouts_on_the_moments_seed():
    valuation = Valuation(LAYOUT, RULES, PlannerConfig(), knowing=False)
    m = moment()
    options = RobotTasker(LAYOUT, RULES).options(m.world, None)
    values = valuation.options(m, options)
    expected = sum(p * valuation.sampled(m, s, options[0]) for s, p in LIKELY)
    assert values.value[options[0]] == expected
    assert set(values.q) == set(options) and not values.timed_out and values.known == {}
    again = Valuation(LAYOUT, RULES, PlannerConfig(), knowing=False).options(m, options)
    assert again.value == values.value, "the same moment, the same values"


def test_the_ranking_prefers_the_current_subtask_on_a_tie_then_the_options_order():
    options = (Subtask.PICKUP_MEAT, Subtask.PICKUP_ONION, Subtask.PICKUP_PLATE)
    values = Values(q={Subtask.PICKUP_MEAT: 1.0, Subtask.PICKUP_ONION: 2.0, Subtask.PICKUP_PLATE: 2.0})
    assert values.ranked(options, None) == [Subtask.PICKUP_ONION, Subtask.PICKUP_PLATE, Subtask.PICKUP_MEAT]
    assert values.ranked(options, Subtask.PICKUP_PLATE)[0] is Subtask.PICKUP_PLATE


def test_past_the_deadline_only_the_first_option_is_valued():
    valuation = Valuation(LAYOUT, RULES, PlannerConfig(), knowing=False)
    m = moment(deadline=time.perf_counter() - 1.0)
    options = RobotTasker(LAYOUT, RULES).options(m.world, None)
    values = valuation.options(m, options)
    assert list(values.q) == [options[0]] and values.timed_out


def test_the_showing_robot_keeps_the_knowing_value_apart_from_the_progress():
    m = moment()
    options = RobotTasker(LAYOUT, RULES).options(m.world, None)
    plain = Valuation(LAYOUT, RULES, PlannerConfig(), knowing=False).options(m, options)
    showing = Valuation(LAYOUT, RULES, PlannerConfig(), knowing=True).options(m, options)
    assert showing.value == plain.value, "the subtask is chosen on the progress alone"
    assert set(showing.known) == {(r, s) for r in options for s, _ in LIKELY}
