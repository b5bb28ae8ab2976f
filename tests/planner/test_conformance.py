"""Conformance over every shipped kitchen (STYLE 10): determinism, solvability, JSON round-trip."""

from __future__ import annotations

import json

import pytest

from planner.kb import initial_kb
from planner.play import TrialSettings, run_trial
from planner.rules import Rules
from planner.state import WorldState, initial_state
from planner.step import step
from study_config import layout_names, load_layout

KITCHENS = layout_names()


@pytest.mark.parametrize("name", KITCHENS)
def test_same_seed_same_trajectory(name):
    layout = load_layout(name)
    first = run_trial(layout, seed=11, record=True)
    again = run_trial(layout, seed=11, record=True)
    assert first.actions == again.actions and first.final == again.final
    other = run_trial(layout, seed=12, record=True)
    assert other.actions != first.actions


@pytest.mark.parametrize("name", KITCHENS)
def test_simulated_pair_delivers_every_order_within_the_horizon(name):
    """At the 2D study's KB delay (1) every trial finishes. At the simulations' delay 3 the paper's models can
    stall (docs/domain.md §3: a belief acknowledged at one place is checked only where the object was last seen;
    §4: the person puts down what its KB gives it no use for and takes a plate again): at most one seed in ten."""
    layout = load_layout(name)
    stalled = []
    for seed in range(10):
        result = run_trial(layout, seed=seed, settings=TrialSettings(kb_delay=1))
        assert result.finished, f"{name} seed {seed}: {result.delivered} delivered in {result.ticks} ticks"
        assert result.score == Rules().orders * Rules().delivery_reward
        stalled += [seed] if not run_trial(layout, seed=seed, settings=TrialSettings(kb_delay=3)).finished else []
    assert len(stalled) <= 1, f"{name}: stalled at delay 3 with seeds {stalled}"


@pytest.mark.parametrize("name", KITCHENS)
def test_every_state_of_a_trial_round_trips_through_json(name):
    layout = load_layout(name)
    rules = Rules()
    trial = run_trial(layout, seed=3, record=True)
    state = initial_state(layout, rules)
    seen = 0
    for human, robot in trial.actions:
        state, _ = step(layout, state, {"human": human, "robot": robot}, rules)
        restored = WorldState.from_dict(json.loads(json.dumps(state.to_dict())))
        assert restored == state and hash(restored) == hash(state)
        seen += 1
    assert seen == trial.ticks and state == trial.final
    assert json.loads(json.dumps(initial_kb(state).to_dict()))["grills"] == list(state.grills)


def test_from_dict_rejects_unknown_objects():
    layout = load_layout("none_3")
    data = initial_state(layout, Rules()).to_dict()
    data["human"]["held"] = "banana"
    with pytest.raises(ValueError, match="banana"):
        WorldState.from_dict(data)
