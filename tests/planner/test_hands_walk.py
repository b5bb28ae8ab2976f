"""The hands walk on predicted views (:func:`planner.hands_walk.hands_walk`) in the wait kitchen
(``steakhouse_wait_kitchen.py``): a robot with a load at (3, 3) walks to the serving counter (7, 1), five ticks by the
shortest way (east along row 3, then north), while the person stands at (4, 5). Facing west they see columns 1–2 (and
(3, 4)), none of the shortest way; facing south, only the cells beside them; facing north, rows 2–3. The person's
poses are given tick by tick, as the robot's rollouts predict them."""

from __future__ import annotations

from steakhouse_wait_kitchen import WAIT_KITCHEN

from planner.fov import view
from planner.geometry import Action, Direction
from planner.hands_walk import hands_walk
from planner.paths import distance, next_pose

LAYOUT = WAIT_KITCHEN
START = ((3, 3), Direction.EAST)
CELLS = ((7, 1),)
SHORTEST = distance(LAYOUT, START, CELLS[0])
PERSON = (4, 5)
NEED = 3


def person(facing: Direction, turn_at: int | None = None, then: Direction = Direction.WEST, ticks: int = 20):
    """The person at (4, 5) facing ``facing``, and ``then`` from tick ``turn_at`` on."""
    return [(PERSON, then if turn_at is not None and t >= turn_at else facing) for t in range(1, ticks + 1)]


def acknowledged(plan, poses, run=0, start=START):
    """The tick at which the person acknowledges the robot's hands along ``plan`` (``NEED`` consecutive ticks in
    their view), ``None`` if they never do; and where the walk ends."""
    pose, streak, ack = start, run, None
    for t, action in enumerate(plan, start=1):
        if action.direction is not None:
            pose = next_pose(LAYOUT, pose, action.direction)
        here, facing = poses[min(t, len(poses)) - 1]
        streak = streak + 1 if pose[0] in view(LAYOUT, here, facing, 120).cells else 0
        if streak >= NEED and ack is None:
            ack = t
    return ack, pose


def walk(futures, budget=6, price=0.5, run=0, start=START):
    return hands_walk(LAYOUT, 120, start, CELLS, futures, NEED, run, budget, price)


def test_the_shortest_way_is_out_of_a_person_facing_west():
    ack, end = acknowledged(walk([(1.0, person(Direction.WEST))], budget=0), person(Direction.WEST))
    assert SHORTEST == 5 and ack is None and distance(LAYOUT, end, CELLS[0]) == 0


def test_the_robot_steps_into_the_view_and_waits_when_that_saves_wrong_ticks():
    """A tick west into the view and two stays: the person knows the load from tick 3 on, rather than never on
    the five-tick way; four extra ticks at 0.5 each are worth it."""
    poses = person(Direction.WEST)
    plan = walk([(1.0, poses)])
    ack, end = acknowledged(plan, poses)
    assert ack is not None and ack <= 4
    assert distance(LAYOUT, end, CELLS[0]) == 0 and SHORTEST < len(plan) <= SHORTEST + 6


def test_a_high_price_or_no_budget_keeps_the_shortest_way():
    poses = person(Direction.WEST)
    for budget, price in ((0, 0.5), (6, 2.0)):
        plan = walk([(1.0, poses)], budget=budget, price=price)
        assert len(plan) == SHORTEST and Action.STAY not in plan


def test_a_person_facing_away_all_along_gets_the_shortest_way():
    plan = walk([(1.0, person(Direction.SOUTH))])
    assert len(plan) == SHORTEST and Action.STAY not in plan


def test_a_person_facing_the_way_sees_the_shortest_walk():
    """Facing north the person sees rows 2 and 3: the shortest way is acknowledged on its third tick."""
    poses = person(Direction.NORTH)
    plan = walk([(1.0, poses)])
    ack, _ = acknowledged(plan, poses)
    assert len(plan) == SHORTEST and ack == NEED


def test_the_walk_follows_the_predicted_turn_not_the_present_view():
    """Facing south now and west from tick 2: the walk goes where the person will look, and is acknowledged.
    Planned on the present view (south all along) it would walk down beside the person instead: no sooner
    acknowledged, and longer."""
    poses = person(Direction.SOUTH, turn_at=2)
    plan = walk([(1.0, poses)], price=0.25)
    ack, _ = acknowledged(plan, poses)
    assert ack is not None and len(plan) > SHORTEST
    present = walk([(1.0, person(Direction.SOUTH))], price=0.25)
    present_ack, _ = acknowledged(present, poses)
    assert present_ack is None or present_ack >= ack
    assert len(present) > len(plan)


def test_the_likelier_hypothesis_decides():
    west, south = person(Direction.WEST), person(Direction.SOUTH)
    likely_west = walk([(0.8, west), (0.2, south)])
    likely_south = walk([(0.2, west), (0.8, south)])
    assert acknowledged(likely_west, west)[0] is not None and len(likely_west) > SHORTEST
    assert len(likely_south) == SHORTEST


def test_ticks_already_in_view_count():
    """Standing in view at (2, 3) for two ticks already, one more tick there is enough: the person knows the load
    from the first tick; a robot not yet seen is known from the third, on a longer walk."""
    start = ((2, 3), Direction.WEST)
    poses = person(Direction.WEST)
    shortest = distance(LAYOUT, start, CELLS[0])
    seen_twice = walk([(1.0, poses)], start=start, run=2)
    assert acknowledged(seen_twice, poses, run=2, start=start)[0] == 1 and len(seen_twice) == shortest + 1
    unseen = walk([(1.0, poses)], start=start, run=0)
    assert acknowledged(unseen, poses, start=start)[0] == NEED and len(unseen) > len(seen_twice)


def test_nothing_to_plan_at_the_station_or_without_a_prediction():
    at_counter = ((7, 2), Direction.NORTH)
    assert walk([(1.0, person(Direction.WEST))], start=at_counter) == ()
    assert walk([]) == ()
