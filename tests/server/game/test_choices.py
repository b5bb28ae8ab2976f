"""What an accepted message does to the participant's cook (``server.game.choices``): a chosen task is taken (and
logged with whether the page offered it) or refused with its reason; keys queue up to three, the fourth refused
with nothing changed; focus, blur and idle are only logged; a choice or key ends the idle stretch."""

from __future__ import annotations

import pytest
from steakhouse_live_parts import Events, engine, world_with

from planner.objects import ONION
from planner.subtasks import Subtask
from server.game.blocked import Blocked
from server.game.choices import apply_choice
from server.game.engine import TrialEngine
from server.protocol.client import AnyClientMessage, Blur, Focus, Idle, InterruptMessage, SelectSubtask
from server.protocol.inbound import ProtocolError
from server.protocol.interrupts import Interrupt
from server.protocol.server import Ack


class Told:
    def __init__(self) -> None:
        self.events, self.blocked, self.acted = Events(), list[Blocked](), 0

    def apply(self, message: AnyClientMessage, on: TrialEngine) -> Ack:
        return apply_choice(message, on, log=self.events, blocked=self.blocked.append, acted=self.act)

    def act(self) -> None:
        self.acted += 1


def test_a_chosen_task_is_taken_logged_with_whether_it_was_offered_and_ends_the_idle_stretch() -> None:
    told, cook = Told(), engine()
    offered = cook.controller.available(cook.world, cook.kb)
    chosen = offered[0]
    ack = told.apply(SelectSubtask(v=1, type="select_subtask", seq=4, subtask=chosen), cook)
    assert (ack.ack, ack.subtask, ack.queued) == (4, chosen.value, 0)
    assert cook.controller.subtask is chosen and told.acted == 1
    assert told.events.kept == [("select_subtask", {"seq": 4, "subtask": chosen.value, "available": True})]
    not_offered = next(s for s in Subtask if s not in offered and s is not Subtask.PICKUP_ONION)
    told.apply(SelectSubtask(v=1, type="select_subtask", seq=5, subtask=not_offered), cook)
    assert told.events.kept[-1][1]["available"] is False


def test_a_task_that_cannot_work_with_what_the_cook_holds_is_refused_with_its_reason() -> None:
    told, cook = Told(), engine(world_with(held=ONION))
    ack = told.apply(SelectSubtask(v=1, type="select_subtask", seq=1, subtask=Subtask.PICKUP_MEAT), cook)
    assert ack.subtask is None and cook.controller.subtask is None and told.acted == 0
    assert [(b.subtask, b.ended) for b in told.blocked] == [(Subtask.PICKUP_MEAT, True)]
    assert told.blocked[0].reason.code == "hands_full" and told.blocked[0].reason.item == ONION
    assert told.events.kinds() == ["select_subtask"]


def test_keys_queue_up_to_three_and_a_fourth_is_refused_with_nothing_changed() -> None:
    told, cook = Told(), engine()
    acks = [told.apply(InterruptMessage(v=1, type="interrupt", seq=seq, action=Interrupt.UP), cook)
            for seq in (1, 2, 3)]
    assert [a.queued for a in acks] == [1, 2, 3] and told.acted == 3
    with pytest.raises(ProtocolError) as refused:
        told.apply(InterruptMessage(v=1, type="interrupt", seq=4, action=Interrupt.LEFT), cook)
    assert refused.value.code == "queue_full" and refused.value.ref == 4
    assert len(cook.controller.queue) == 3 and told.events.kinds() == ["interrupt"] * 3
    assert told.events.kept[0][1] == {"seq": 1, "action": "up", "subtask": None}


def test_stop_ends_the_task_and_leaves_the_cook_idle() -> None:
    told, cook = Told(), engine()
    chosen = cook.controller.available(cook.world, cook.kb)[0]
    told.apply(SelectSubtask(v=1, type="select_subtask", seq=1, subtask=chosen), cook)
    ack = told.apply(InterruptMessage(v=1, type="interrupt", seq=2, action=Interrupt.STOP), cook)
    assert ack.subtask is None and not cook.controller.has_action()
    assert told.acted == 1, "a stop leaves the cook nothing to do: the idle stretch goes on"


def test_focus_blur_and_idle_are_only_logged() -> None:
    told, cook = Told(), engine()
    messages = (Focus(v=1, type="focus", seq=1), Blur(v=1, type="blur", seq=2),
                Idle(v=1, type="idle", seq=3, idle_ms=900))
    for message in messages:
        ack = told.apply(message, cook)
        assert (ack.subtask, ack.queued) == (None, 0)
    assert told.events.kept == [("focus", {"seq": 1}), ("blur", {"seq": 2}), ("idle", {"seq": 3, "idle_ms": 900})]
    assert told.acted == 0 and not cook.controller.has_action()
