"""The running averages of the subtask values (:mod:`planner.smoothing`)."""

from __future__ import annotations

from planner.objects import MEAT
from planner.smoothing import ValueAverages
from planner.subtasks import Subtask


def test_value_averages_restart_when_the_robots_hands_or_the_orders_change():
    values = ValueAverages(0.5)
    values.restart_on((None, 2))
    assert values.fold(Subtask.PICKUP_MEAT, 10.0) == 10.0
    assert values.fold(Subtask.PICKUP_MEAT, 20.0) == 15.0
    values.restart_on((None, 2))
    assert values.fold(Subtask.PICKUP_MEAT, 5.0) == 10.0
    values.restart_on((MEAT, 2))
    assert values.fold(Subtask.PICKUP_MEAT, 5.0) == 5.0
