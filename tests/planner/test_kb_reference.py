"""Our KB and KB gap against the reference implementation's own outputs (docs/domain.md §3 and §6).

``kb_reference.json`` beside this file holds trials of ours (kitchen, KB delay, the joint actions) and, for every
state of each, what the reference's own functions computed on it (``SteakLimitVisionHumanModel.update`` and
``get_kb_key`` for the person's KB, ``update_world_kb_log`` for the world, ``kb_diff_measure`` for the gap and the
trial's ``kb_diff_freq`` / ``kb_diff_avg``), run by ``benchmarks/planner/kb_reference.py`` (its provenance is in the
file). Replaying the actions through our world and our KB must give the same on every state.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from planner.events import Event
from planner.geometry import Action
from planner.kb import KnowledgeBase, initial_kb, update_kb
from planner.rules import Rules
from planner.state import initial_state
from planner.step import step
from planner.summary import kb_diff, kb_diff_trial, reference_key
from study_config import load_layout

FIXTURE = json.loads((Path(__file__).parent / "kb_reference.json").read_text(encoding="utf-8"))
ACTIONS = {"n": Action.NORTH, "s": Action.SOUTH, "e": Action.EAST, "w": Action.WEST, "x": Action.STAY,
           "i": Action.INTERACT}
TRIALS = FIXTURE["trials"]


def test_the_fixture_is_the_reference_on_enough_states_of_both_delays():
    assert FIXTURE["provenance"]["repository"] == "SophieHsu/FOV-aware-planner"
    assert sum(len(t["kb"]) for t in TRIALS) >= 2000
    assert {t["delay"] for t in TRIALS} == {1, 3}
    with_gap = sum(any(c != "0" for c in t["diff"][i:i + 4]) for t in TRIALS for i in range(0, len(t["diff"]), 4))
    assert with_gap > 500, "the states must include gaps to compare"


@pytest.mark.parametrize("trial", TRIALS, ids=lambda t: f"{t['kitchen']}-{t['robot']}-{t['seed']}-d{t['delay']}")
def test_our_kb_and_gap_are_the_references_on_every_state(trial):
    layout, rules = load_layout(trial["kitchen"]), Rules()
    world = initial_state(layout, rules)
    kb: KnowledgeBase = initial_kb(world)
    codes = trial["actions"]
    diffs = []
    for t in range(len(codes) // 2):
        human, robot = ACTIONS[codes[2 * t]], ACTIONS[codes[2 * t + 1]]
        world, events = step(layout, world, {"human": human, "robot": robot}, rules)
        own: list[Event] = [e for e in events if e.agent == "human"]
        kb = update_kb(kb, layout, world, angle=120.0, kb_delay=trial["delay"], own_events=own)
        ours_kb, ours_world = reference_key(kb), reference_key(world)
        assert (ours_kb, ours_world) == (trial["kb"][t], trial["world"][t]), f"tick {t + 1}"
        diff = kb_diff(ours_kb, ours_world)
        assert "".join(map(str, diff.values())) == trial["diff"][4 * t:4 * t + 4], f"tick {t + 1}"
        diffs.append(diff)
    assert len(diffs) == len(trial["kb"])
    freq, avg, _mean = kb_diff_trial(diffs)
    assert round(freq, 2) == trial["kb_diff_freq"]
    assert (None if avg is None else round(avg, 2)) == trial["kb_diff_avg"]
