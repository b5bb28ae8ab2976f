"""The behaviour measures (planner.behaviours; docs/domain.md §6, "Behaviours") on hand-written ticks."""

from __future__ import annotations

from planner.behaviours import Frame, holdings, measure
from planner.objects import CLEAN_PLATE, DISH, MEAT, STEAK_PLATE


def frames(spec: str, held: str | None = MEAT) -> list[Frame]:
    """``.`` empty-handed, ``h`` holding unseen, ``H`` holding in view."""
    return [Frame(None if c == "." else held, c == "H") for c in spec]


def test_a_pickup_counts_as_shown_only_with_kb_delay_consecutive_ticks_in_view():
    assert measure(frames("..hHHHh.."), 3).shown == 1
    assert measure(frames("..hHHhH.."), 3).shown == 0
    assert measure(frames("..hHHhH.."), 2).shown == 1
    counted = measure(frames("hhh..HH"), 3)
    assert (counted.holdings, counted.shown, counted.shown_rate) == (2, 0, 0.0)


def test_a_changed_object_starts_a_new_holding():
    ticks = [Frame(CLEAN_PLATE, True), Frame(CLEAN_PLATE, True), Frame(STEAK_PLATE, True), Frame(STEAK_PLATE, True),
             Frame(STEAK_PLATE, True)]
    assert holdings(ticks) == [(0, 2), (2, 5)]
    assert measure(ticks, 3).shown == 1


def test_a_dish_trip_counts_only_when_the_robot_delivers_it():
    trip = [Frame(DISH, True), Frame(DISH, False), Frame(DISH, False), Frame(DISH, True),
            Frame(None, False, delivered=True)]
    b = measure(trip, 3)
    assert (b.trips, b.trip_share) == (1, 0.5)
    dropped = trip[:-1] + [Frame(None, False)]
    assert measure(dropped, 3).trips == 0
    assert measure(trip[:-1], 3).trips == 0
    assert (measure(trip, 3) + measure(trip, 3)).trip_share == 0.5
