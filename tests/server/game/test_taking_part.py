"""The round's taking part so far (``server.game.taking_part``): counted from the round's events and steps as they
happen, it says while the participant can still act that the round, ended now, would not count; a practice round
is never judged, nor a round once its robot's health made it invalid."""

from __future__ import annotations

from steakhouse_live_parts import engine, world_with

from planner.geometry import Action, Direction
from server.game.taking_part import TakingPart
from server.protocol.interrupts import Interrupt
from study_config.study.validity import Validity


def test_a_round_without_a_choice_or_key_would_not_count() -> None:
    part = TakingPart(Validity(), 5.0, judged=True)
    problem = part.problem()
    assert problem is not None and problem.rule == "no_actions"
    part.note("focus", {"seq": 1})
    assert part.problem() is not None
    part.note("interrupt", {"seq": 2, "action": "stop"})
    assert part.problem() is None
    assert (part.activity().interrupts, part.activity().key_actions) == (1, 0), "a stop is no key of the cook's"
    part.note("interrupt", {"seq": 3, "action": "up"})
    assert part.activity().key_actions == 1


def test_waiting_counts_toward_the_idle_share() -> None:
    part = TakingPart(Validity(max_idle_pct=50), 5.0, judged=True)
    part.note("select_subtask", {"seq": 1, "subtask": "pickup_onion", "available": True})
    cook = engine()
    for _ in range(10):
        part.stepped(cook.advance(Action.STAY))
    problem = part.problem()
    assert problem is not None and problem.rule == "idle", "ten idle ticks of ten"
    part.note("wait", {"seconds": 3.0})
    activity = part.activity()
    assert (activity.ticks, activity.idle_ticks, activity.waited_seconds) == (10, 10, 3.0)


def test_the_cooks_task_steps_are_counted_and_a_blocked_key_is_none() -> None:
    part = TakingPart(Validity(), 5.0, judged=True)
    cook = engine(world_with(pos=(6, 2), facing=Direction.NORTH))  # facing the onion crate
    cook.controller.interrupt(Interrupt.INTERACT)
    part.stepped(cook.advance(Action.STAY))
    cook.controller.interrupt(Interrupt.UP)  # into the crate: a turn at most, nothing changes
    part.stepped(cook.advance(Action.STAY))
    activity = part.activity()
    assert (activity.ticks, activity.task_steps, activity.robot_task_steps, activity.idle_ticks) == (2, 1, 0, 0)


def test_practice_is_never_judged() -> None:
    assert TakingPart(Validity(), 5.0, judged=False).problem() is None


def test_a_round_the_robot_made_invalid_is_no_longer_judged() -> None:
    part = TakingPart(Validity(), 5.0, judged=True)
    assert part.problem() is not None, "no action yet: it would not count"
    part.note("trial_invalid", {"invalid_reason": "missed 12 % of its decision deadlines"})
    assert part.problem() is None, "a broken robot's round is not the participant's to answer for"
