"""No livelock with any partner: over generated kitchens × seeds × robots × partners (the
simulated person, the adversary, a person who never moves), every trial that can be finished finishes.

With the simulated person and the adversary (whose disruption ends after its budget) every trial can be
finished; with a still person, those where one agent can reach every kind of station without passing the
person's cell (:func:`planner.alone.solo_possible`). A failure names the kitchen (generator seed), the
simulation seed, the robot and the partner, for ``benchmarks/planner/no_stall.py`` to replay. Few examples,
derandomised, so the suite stays short and repeatable; ``no_stall.py`` runs the wide sweep."""

from __future__ import annotations

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from planner.alone import solo_possible
from planner.layout_gen import generate_named
from planner.partner import PARTNERS, partner_model
from planner.planner_config import PlannerConfig
from planner.play import run_trial
from planner.robots import make_robot
from planner.rules import Rules
from planner.state import initial_state

RULES = Rules()
ROBOTS = ("fov_aware", "fov_aware_showing", "baseline", "no_rollout")


@settings(max_examples=5, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
@given(generator_seed=st.integers(1000, 1099), seed=st.integers(0, 9), robot=st.sampled_from(ROBOTS),
       partner=st.sampled_from(PARTNERS))
def test_every_trial_that_can_be_finished_finishes(generator_seed, seed, robot, partner):
    layout = generate_named(generator_seed)
    if partner == "still" and not solo_possible(layout, initial_state(layout, RULES)):
        return
    result = run_trial(layout, seed, robot=make_robot(robot, layout, RULES, PlannerConfig()),
                       human=partner_model(partner, layout, RULES))
    assert result.finished, (f"kitchen {layout.name} (generator seed {generator_seed}) seed {seed}: {robot} with "
                             f"the {partner} partner unfinished at tick {result.ticks}, "
                             f"{RULES.orders - result.delivered} orders left")
