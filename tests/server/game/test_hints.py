"""What the participant is told beside the state (``server.game.hints``): why their task is blocked (logged once it
ended), one stall hint per stuck stretch, a nudge per idle interval, the countdown of the round's last minute once per
connection, and, from the second nudge on, the warning that the round so far would not count (never in practice)."""

from __future__ import annotations

import asyncio
from typing import Any

from steakhouse_live_parts import Events, HandClock, closed, connection, engine, opened

from planner.geometry import Action
from planner.subtasks import Subtask
from server.game.blocked import Blocked, Reason
from server.game.hints import Hints
from server.game.link import ParticipantLink
from server.game.round_time import RoundTime
from server.game.taking_part import TakingPart
from study_config.study.validity import Validity

NUDGE_S = 10.0


class Told:
    def __init__(self, judged: bool = True, limit_s: float | None = None, stall_ticks: int = 2) -> None:
        self.events, self.clock = Events(), HandClock()
        self.link = ParticipantLink(10_000, self.events)
        self.times = RoundTime(self.clock, limit_s, NUDGE_S)
        self.part = TakingPart(Validity(), 5.0, judged=judged)
        self.hints = Hints(stall_ticks, self.link, self.events, self.times, self.part)
        self.conn, self.socket = connection()

    def connect(self) -> None:
        opened(self.link, self.conn)
        self.times.connected()
        self.times.idle()
        self.events.kept.clear()


def test_a_blocked_task_is_told_and_logged_once_it_ended() -> None:
    async def scenario() -> tuple[list[dict[str, Any]], list[Any]]:
        told = Told()
        told.connect()
        told.hints.blocked(Blocked(Subtask.CHOP_ONION, Reason("robot_in_way"), ended=False))
        told.hints.blocked(Blocked(Subtask.CHOP_ONION, Reason("not_chopped", place="board"), ended=True))
        return (await closed(told.conn, told.socket)).sent[2:], told.events.kept

    sent, events = asyncio.run(scenario())
    assert [(m["type"], m["reason"], m["ended"]) for m in sent] == [
        ("blocked", "robot_in_way", False), ("blocked", "not_chopped", True)]
    assert events == [("subtask_blocked", {"subtask": "chop_onion", "reason": "not_chopped", "item": None,
                                           "place": "board"})]


def test_one_stall_hint_per_stuck_stretch() -> None:
    async def scenario() -> tuple[list[int], list[dict[str, Any]], list[Any]]:
        told, cook = Told(stall_ticks=2), engine()
        told.connect()
        hinted_at: list[int] = []
        for tick in range(1, 7):
            told.hints.stepped(cook, cook.advance(Action.STAY))
            if told.hints.stall_hints > len(hinted_at):
                hinted_at.append(tick)
        return hinted_at, (await closed(told.conn, told.socket)).sent[2:], told.events.kept

    hinted_at, sent, events = asyncio.run(scenario())
    assert hinted_at == [3], "the potential stood still for two steps after the first; then no more while stuck"
    assert [m["type"] for m in sent] == ["stall_hint"]
    assert events == [("stall_hint", {"code": sent[0]["code"], "text": sent[0]["text"]})]


def test_a_nudge_each_idle_interval_and_a_warning_from_the_second_on_when_the_round_would_not_count() -> None:
    async def scenario(judged: bool) -> tuple[list[Any], list[Any]]:
        told = Told(judged=judged)
        told.connect()
        told.hints.nudge()  # nothing due yet
        for _ in range(2):
            told.clock.advance(NUDGE_S)
            told.hints.nudge()
        return [(m["type"], m.get("repeat", m.get("rule"))) for m in (await closed(told.conn, told.socket)).sent[2:]], \
            told.events.kinds()

    sent, kinds = asyncio.run(scenario(judged=True))
    assert sent == [("nudge", 1), ("nudge", 2), ("warning", "no_actions")]
    assert kinds == ["nudge", "nudge", "engagement_warning"]
    practice, _ = asyncio.run(scenario(judged=False))
    assert practice == [("nudge", 1), ("nudge", 2)], "a practice round is never judged"


def test_nothing_is_told_to_nobody_and_the_due_nudge_waits_for_them() -> None:
    async def scenario() -> tuple[list[str], list[Any]]:
        told = Told()
        told.times.connected()
        told.times.idle()
        told.clock.advance(NUDGE_S)
        told.hints.nudge()  # nobody connected: nothing sent, nothing taken
        told.connect()
        told.clock.advance(NUDGE_S)  # the stretch is counted again from the reconnection
        told.hints.nudge()
        return [m["type"] for m in (await closed(told.conn, told.socket)).sent[2:]], told.events.kept

    sent, events = asyncio.run(scenario())
    assert sent == ["nudge"] and events == [("nudge", {"repeat": 1})]


def test_the_last_minute_is_counted_down_once() -> None:
    async def scenario() -> list[Any]:
        told = Told(limit_s=100.0, judged=False)
        told.connect()
        told.times.acted()  # busy: no nudges
        told.clock.advance(30.0)
        told.hints.nudge()
        told.clock.advance(15.0)
        told.hints.nudge()
        told.clock.advance(5.0)
        told.hints.nudge()
        return [(m["type"], m["seconds_left"]) for m in (await closed(told.conn, told.socket)).sent[2:]]

    assert asyncio.run(scenario()) == [("countdown", 55.0)]
