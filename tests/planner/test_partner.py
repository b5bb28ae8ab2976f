"""A simulated person who differs from the robot's model of them (:class:`planner.partner.Person`,
:class:`planner.partner.ErraticHuman`): the robustness benchmarks' person."""

from __future__ import annotations

import numpy as np

from planner.human import HumanMemory, HumanModel
from planner.kb import initial_kb
from planner.layout_gen import generate_named
from planner.partner import ErraticHuman, Person
from planner.rules import Rules
from planner.state import initial_state

RULES = Rules()
LAYOUT = generate_named(5)


def actions(model: HumanModel, seed: int, ticks: int = 40) -> list[str]:
    world = initial_state(LAYOUT, RULES)
    kb, memory, rng = initial_kb(world), HumanMemory(), np.random.default_rng(seed)
    out = []
    for _ in range(ticks):
        action, memory = model.act(world, kb, memory, rng)
        out.append(action.value)
    return out


def test_a_person_without_random_actions_is_the_simulated_person():
    assert Person(90.0, 1).model(LAYOUT, RULES) is None, "run_trial's own simulated person plays"
    erratic = Person(120.0, 3, 0.25).model(LAYOUT, RULES)
    assert isinstance(erratic, ErraticHuman) and erratic.random_share == 0.25


def test_random_actions_replace_the_models_on_their_share_of_ticks_reproducibly():
    plain = actions(HumanModel(LAYOUT, RULES), 7)
    always = actions(ErraticHuman(LAYOUT, RULES, random_share=1.0), 7)
    assert len(set(always)) >= 5, "every tick a random action of the six"
    assert sum(a != b for a, b in zip(always, plain, strict=True)) > len(plain) // 2
    assert always == actions(ErraticHuman(LAYOUT, RULES, random_share=1.0), 7), "drawn from the person's stream"
    assert actions(ErraticHuman(LAYOUT, RULES, random_share=0.1), 7) != always
