"""The admission line: slots up to the capacity, first come first served, resumes first, leaving frees."""

from __future__ import annotations

import asyncio

import pytest

from server.game.admission import Admission, default_capacity


def test_the_default_capacity_follows_the_cores_up_to_one_core_of_game_loops():
    assert default_capacity(1) == 20
    assert default_capacity(2) == 40
    assert default_capacity(4) == default_capacity(8) == 53


def test_slots_up_to_the_capacity_then_a_line_in_arrival_order():
    async def scenario():
        admission = Admission(2)
        assert admission.try_enter(1) and admission.try_enter(2)
        assert not admission.try_enter(3)
        third, fourth = admission.enqueue(3), admission.enqueue(4)
        positions = (admission.position(third), admission.position(fourth))
        admission.release(1)
        granted = (third.granted.is_set(), fourth.granted.is_set(), admission.position(fourth))
        return positions, granted, admission.live, admission.holds(3)

    positions, granted, live, holds = asyncio.run(scenario())
    assert positions == (1, 2)
    assert granted == (True, False, 1)
    assert live == 2 and holds


def test_a_newcomer_cannot_overtake_the_line_and_a_resume_goes_first():
    async def scenario():
        admission = Admission(1)
        admission.try_enter(1)
        waiting = admission.enqueue(2)
        resuming = admission.enqueue(3, first=True)
        admission.release(1)
        overtaken = admission.try_enter(4)
        return admission.position(waiting), resuming.granted.is_set(), overtaken

    assert asyncio.run(scenario()) == (1, True, False)


def test_leaving_the_line_moves_the_others_up_and_tells_them():
    async def scenario():
        admission = Admission(1)
        admission.try_enter(1)
        first, second = admission.enqueue(2), admission.enqueue(3)
        second.changed.clear()
        admission.leave(first)
        return admission.position(second), second.changed.is_set(), admission.waiting

    assert asyncio.run(scenario()) == (1, True, 1)


def test_a_granted_ticket_that_leaves_frees_its_slot():
    async def scenario():
        admission = Admission(1)
        admission.try_enter(1)
        ticket = admission.enqueue(2)
        admission.release(1)
        admission.leave(ticket)
        return admission.live, admission.try_enter(3)

    assert asyncio.run(scenario()) == (0, True)


def test_the_expected_wait_counts_rounds_of_slots():
    admission = Admission(2)
    assert admission.eta_s(1, 80.0) == 80.0
    assert admission.eta_s(3, 80.0) == 160.0


def test_a_capacity_below_one_is_refused():
    with pytest.raises(ValueError, match="at least 1"):
        Admission(0)
