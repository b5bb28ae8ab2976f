"""The behaviour measures (planner.behaviours; docs/domain.md §6, "Behaviours") on hand-written ticks."""

from __future__ import annotations

import pytest

from planner.behaviours import Frame, HandsGap, frame_of, hands_gap, holdings, measure
from planner.objects import CLEAN_PLATE, DISH, MEAT, STEAK_PLATE
from planner.perception import FOV_ANGLE, KB_DELAY
from planner.play import TrialSettings, run_trial
from planner.rules import Rules
from planner.state import initial_state
from planner.step import step
from study_config import load_layout


def frames(spec: str, held: str | None = MEAT) -> list[Frame]:
    """``.`` empty-handed, ``h`` holding unseen, ``H`` holding in view."""
    return [Frame(None if c == "." else held, c == "H") for c in spec]


def test_a_pickup_counts_as_shown_only_with_kb_delay_consecutive_ticks_in_view():
    assert measure(frames("..hHHHh.."), 3).shown == 1
    assert measure(frames("..hHHhH.."), 3).shown == 0
    assert measure(frames("..hHHhH.."), 2).shown == 1
    counted = measure(frames("hhh..HH"), 3)
    assert (counted.holdings, counted.shown, counted.shown_rate) == (2, 0, 0.0)


def test_ticks_in_view_before_the_pickup_count_toward_showing_it():
    """The person's count of the robot runs on whatever its hands do (docs/domain.md §3): a robot watched for 3
    ticks shows what it picks up at the very tick it picks it up."""
    watched = [Frame(None, True)] * 3 + [Frame(MEAT, True), Frame(MEAT, False)]
    assert measure(watched, 3).shown == 1
    assert measure([Frame(None, True), Frame(MEAT, True), Frame(MEAT, False)], 3).shown == 0


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


def test_the_hands_gap_splits_the_ticks_the_kb_is_wrong_about_the_robots_hands():
    # picked up in view after 2 ticks unseen: wrong until its third tick in view; a person watching from the
    # start would have known from the third tick, so these 2 ticks are unseen, not lag
    assert hands_gap(frames("..HHHH"), 3) == HandsGap(ticks=6, lag=0, unseen=2, stale=0)
    # picked up out of view: unseen until it has stood 3 ticks in view
    assert hands_gap(frames("..hhhhHHH"), 3) == HandsGap(ticks=9, lag=0, unseen=6, stale=0)
    # shown from the first tick (2 ticks of lag), then put down out of view: the person still believes it holds it
    assert hands_gap(frames("HHHH...."), 3) == HandsGap(ticks=8, lag=2, unseen=0, stale=4)
    # a load never seen and put down: the person was never wrong about the empty hands that follow
    assert hands_gap(frames("hhhh...."), 3) == HandsGap(ticks=8, lag=2, unseen=2, stale=0)
    # watched all along: a change of hands is known at once, the only wrong ticks are the first two
    watched = [Frame(MEAT, True)] * 3 + [Frame(None, True)] * 2
    assert hands_gap(watched, 3) == HandsGap(ticks=5, lag=2, unseen=0, stale=0)


def test_the_hands_gap_counts_what_the_kb_counts_in_a_simulated_trial():
    layout = load_layout("none_3")
    rules = Rules()
    result = run_trial(layout, 3, TrialSettings(FOV_ANGLE, KB_DELAY, rules), record=True)
    gap = result.hands
    assert gap.ticks == result.ticks and gap.wrong > 0 and gap.unseen > 0
    assert 100.0 * gap.wrong / gap.ticks == pytest.approx(result.gap_component_pct["robot_held"])
    # the frames the trial measured are those of its recorded actions replayed
    world = initial_state(layout, rules)
    played = []
    for h_action, r_action in result.actions:
        world, events = step(layout, world, {"human": h_action, "robot": r_action}, rules)
        played.append(frame_of(layout, world, events, FOV_ANGLE))
    assert hands_gap(played, KB_DELAY) == gap and measure(played, KB_DELAY) == result.behaviours
    assert result.behaviours.holdings > 0


def test_where_the_kb_places_the_robot_is_measured_against_where_it_is():
    layout = load_layout("none_3")
    omniscient = run_trial(layout, 1, TrialSettings(360.0, 0, Rules()))
    assert (omniscient.robot_place_cells, omniscient.robot_place_wrong_pct) == (0.0, 0.0)
    limited = run_trial(layout, 1, TrialSettings(FOV_ANGLE, KB_DELAY, Rules()))
    assert limited.robot_place_cells > 0 and 0 < limited.robot_place_wrong_pct < 100
