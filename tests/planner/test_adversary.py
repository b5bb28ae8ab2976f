"""The adversarial participant (planner/adversary.py) and the no-stall check in small: every planner
finishes trials with it once its bounded disruption ends (benchmarks/planner/no_stall.py runs the full set)."""

from __future__ import annotations

import pytest

from planner.adversary import (
    DISRUPTIVE,
    AdversarialHuman,
    AdversaryConfig,
    Mode,
    last_progress_tick,
    narrowest_stations,
)
from planner.layout import access_cells
from planner.layout_gen import generate_named
from planner.planner_config import PlannerConfig
from planner.play import run_trial
from planner.robots import StayRobot, make_robot
from planner.rules import Rules
from planner.state import initial_state
from planner.step import step
from study_config import load_layout


def _only(mode: Mode) -> tuple[float, float, float, float, float]:
    random_task, block, interrupt, idle, cooperate = (1.0 if m is mode else 0.0 for m in Mode)
    return random_task, block, interrupt, idle, cooperate


ONLY = {mode: _only(mode) for mode in Mode}
"""Weights that draw a single mode."""


@pytest.mark.parametrize("robot", ["fov_aware", "baseline", "no_rollout"])
def test_every_planner_finishes_with_the_adversary(robot):
    for kitchen, seed in ((load_layout("none_3"), 2), (generate_named(3), 0)):
        human = AdversarialHuman(kitchen, Rules(), AdversaryConfig(budget=40))
        result = run_trial(kitchen, seed, robot=make_robot(robot, kitchen, Rules(), PlannerConfig()),
                           human=human)
        assert result.finished, f"{robot} stalled on {kitchen.name} seed {seed} at tick {result.ticks}"
        assert set(human.history[:40]) & set(DISRUPTIVE)


def test_the_adversary_stands_in_the_only_access_cell_of_a_station():
    layout = load_layout("none_3")
    rules = Rules()
    human = AdversarialHuman(layout, rules, AdversaryConfig(budget=80, phase=(80, 80), weights=ONLY[Mode.BLOCK]))
    result = run_trial(layout, 4, robot=StayRobot(), human=human, record=True)
    world, stood = initial_state(layout, rules), []
    for h, r in result.actions[:80]:
        world, _ = step(layout, world, {"human": h, "robot": r}, rules)
        stood.append(world.human.pos)
    spots = {cell for station in narrowest_stations(layout) for cell in access_cells(layout, station)}
    assert all(len(access_cells(layout, s)) == 1 for s in narrowest_stations(layout))
    assert stood[-1] in spots and stood[-30:] == [stood[-1]] * 30


def test_it_stands_still_for_long_stretches_then_plays_as_the_simulated_human():
    layout = load_layout("mid_2")
    human = AdversarialHuman(layout, Rules(), AdversaryConfig(budget=40, idle=(40, 40), weights=ONLY[Mode.IDLE]))
    still = run_trial(layout, 1, human=human, record=True)
    assert [h.value for h, _ in still.actions[:40]] == ["stay"] * 40
    assert human.history[:40] == [Mode.IDLE] * 40 and set(human.history[40:]) == {Mode.COOPERATE}
    assert still.finished


def test_disruption_never_exceeds_the_budget():
    layout = generate_named(5)
    human = AdversarialHuman(layout, Rules(), AdversaryConfig(budget=70))
    run_trial(layout, 3, human=human)
    assert sum(m is not Mode.COOPERATE for m in human.history) <= 70
    first_calm = max(i for i, m in enumerate(human.history) if m is not Mode.COOPERATE) + 1
    assert set(human.history[first_calm:]) <= {Mode.COOPERATE}


def test_random_subtasks_and_interrupts_leave_a_trial_the_simulated_team_can_finish():
    layout = load_layout("side_2")
    weights = (0.5, 0.0, 0.5, 0.0, 0.0)
    human = AdversarialHuman(layout, Rules(), AdversaryConfig(budget=120, weights=weights))
    result = run_trial(layout, 6, human=human, record=True)
    assert set(human.history[:120]) == {Mode.RANDOM_TASK, Mode.INTERRUPT}
    assert result.finished
    assert 0 < last_progress_tick(layout, Rules(), result.actions) == result.ticks


def test_same_seed_same_adversarial_trial():
    layout = load_layout("none_1")
    runs = [run_trial(layout, 9, human=AdversarialHuman(layout, Rules()), record=True) for _ in range(2)]
    assert runs[0].actions == runs[1].actions and runs[0].final == runs[1].final


@pytest.mark.parametrize("bad", [{"budget": -1}, {"phase": (0, 3)}, {"idle": (9, 2)}, {"weights": (0, 0, 0, 0, 0)}])
def test_bad_configs_name_the_field(bad):
    with pytest.raises(ValueError, match=next(iter(bad))):
        AdversaryConfig(**bad)
