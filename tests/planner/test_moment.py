"""One decision's frozen situation (:mod:`planner.moment`)."""

from __future__ import annotations

import dataclasses
import time

import pytest

from planner.flicker import FlickerWatch
from planner.kb import initial_kb
from planner.moment import Moment
from planner.rules import Rules
from planner.state import initial_state
from study_config import load_layout


def moment(human_still: int, deadline: float | None) -> Moment:
    world = initial_state(load_layout("practice"), Rules())
    return Moment(world, initial_kb(world), (), 0, 42, human_still, False, True, None, FlickerWatch(), deadline)


def test_a_person_still_two_ticks_is_parked_and_a_passed_deadline_is_late():
    assert not moment(1, None).parked and moment(2, None).parked
    assert not moment(0, None).late() and moment(0, time.perf_counter() - 1).late()
    assert not moment(0, time.perf_counter() + 60).late()


def test_a_moment_cannot_change():
    with pytest.raises(dataclasses.FrozenInstanceError):
        moment(0, None).seed = 1  # type: ignore[misc]
