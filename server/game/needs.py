"""What each subtask needs in the cook's hands (docs/domain.md §1, §4).

Holding something forces its continuation, so most subtasks can only work with one thing in hand: a clean
plate takes the steak, a plated steak takes the garnish, the dish is delivered, meat goes on the grill, …;
every pickup, chopping and washing needs empty hands; putting something on a counter needs something.

The participant always knows what they hold, so the task buttons are disabled from this table without
revealing anything out of view; the table reaches the browser in ``hello.needs``.
"""

from __future__ import annotations

from typing import Final

from planner.objects import CLEAN_PLATE, DIRTY_PLATE, DISH, MEAT, ONION, STEAK_PLATE
from planner.subtasks import Subtask

NOTHING: Final = "nothing"
"""Empty hands."""
SOMETHING: Final = "something"
"""Anything at all in hand."""

NEEDS: dict[Subtask, str] = {
    Subtask.PICKUP_MEAT: NOTHING, Subtask.PICKUP_ONION: NOTHING, Subtask.PICKUP_PLATE: NOTHING,
    Subtask.PICKUP_CLEAN_PLATE: NOTHING, Subtask.CHOP_ONION: NOTHING, Subtask.WASH_PLATE: NOTHING,
    Subtask.PICKUP_STEAK: CLEAN_PLATE, Subtask.PICKUP_GARNISH: STEAK_PLATE, Subtask.DELIVER_DISH: DISH,
    Subtask.DROP_MEAT: MEAT, Subtask.DROP_ONION: ONION, Subtask.DROP_PLATE: DIRTY_PLATE,
    Subtask.DROP_ON_COUNTER: SOMETHING,
}
"""Subtask → what must be in hand: :data:`NOTHING`, :data:`SOMETHING` or an object name."""


def hands_fit(subtask: Subtask, held: str | None) -> bool:
    """Whether ``subtask`` can work with ``held`` in the cook's hands."""
    need = NEEDS[subtask]
    if need == NOTHING:
        return held is None
    if need == SOMETHING:
        return held is not None
    return held == need
