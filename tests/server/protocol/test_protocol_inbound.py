"""Checking client messages: each failure has its code, sequence numbers only move forward, and no input
whatsoever raises anything but a typed ``ProtocolError``."""

from __future__ import annotations

import json

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planner.subtasks import Subtask
from server.protocol.client import Heartbeat, InterruptMessage, SelectSubtask
from server.protocol.inbound import Inbound, ProtocolError


def msg(**fields) -> str:
    return json.dumps({"v": 1, **fields})


def code_of(inbound: Inbound, text: str | None, data: bytes | None = None) -> tuple[str, int | None]:
    with pytest.raises(ProtocolError) as info:
        inbound.check(text, data)
    return info.value.code, info.value.ref


def test_valid_messages_parse_into_typed_models():
    inbound = Inbound(4096)
    select = inbound.check(msg(seq=1, type="select_subtask", subtask="chop_onion"))
    assert isinstance(select, SelectSubtask) and select.subtask is Subtask.CHOP_ONION
    beat = inbound.check(msg(seq=2, type="heartbeat", client_time=12))
    assert isinstance(beat, Heartbeat) and beat.client_time == 12.0
    assert isinstance(inbound.check(msg(seq=3, type="interrupt", action="stop")), InterruptMessage)


def test_sequence_numbers_only_move_forward_once_accepted():
    inbound = Inbound(4096)
    first = inbound.check(msg(seq=5, type="focus"))
    assert inbound.last_seq == 0, "checking alone does not consume the number"
    inbound.accept(first.seq)
    assert code_of(inbound, msg(seq=5, type="focus")) == ("bad_seq", 5)
    assert code_of(inbound, msg(seq=4, type="blur")) == ("bad_seq", 4)
    assert inbound.check(msg(seq=9, type="blur")).seq == 9, "gaps are allowed"


@pytest.mark.parametrize("text,code", [
    ("{", "bad_json"), ('"text"', "invalid_message"), ("null", "invalid_message"),
    (json.dumps({"seq": 1, "type": "focus"}), "unsupported_version"),
    (json.dumps({"v": True, "seq": 1, "type": "focus"}), "unsupported_version"),
    (msg(seq=0, type="focus"), "invalid_message"), (msg(seq=1.0, type="focus"), "invalid_message"),
    (msg(seq=True, type="focus"), "invalid_message"), (msg(seq=1), "unknown_type"),
    (msg(seq=1, type="Focus"), "unknown_type"), (msg(seq=1, type="focus", extra=1), "invalid_message"),
    (msg(seq=1, type="idle", idle_ms=-1), "invalid_message"), (msg(seq=1, type="idle", idle_ms=1.5), "invalid_message"),
    (msg(seq=1, type="heartbeat", client_time="now"), "invalid_message"),
    (msg(seq=1, type="select_subtask", subtask=None), "invalid_message"),
    (msg(seq=1, type="interrupt"), "invalid_message"),
])
def test_each_problem_has_its_code(text, code):
    assert code_of(Inbound(4096), text)[0] == code


def test_size_and_frame_limits():
    inbound = Inbound(256)
    assert code_of(inbound, msg(seq=1, type="focus", pad="é" * 200)) == ("too_large", None)
    assert code_of(inbound, None, b"{}") == ("bad_frame", None)


@settings(max_examples=400, deadline=None)
@given(st.one_of(
    st.text(max_size=300),
    st.recursive(st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=20),
                 lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=10), inner, max_size=5),
                 max_leaves=20).map(json.dumps),
    st.fixed_dictionaries({"v": st.just(1), "seq": st.integers(-2, 5),
                           "type": st.sampled_from(["select_subtask", "interrupt", "heartbeat", "idle", "x"])},
                          optional={"subtask": st.text(max_size=12), "action": st.text(max_size=8),
                                    "client_time": st.floats(allow_nan=True), "idle_ms": st.integers()},
                          ).map(json.dumps),
))
def test_no_input_raises_anything_but_a_protocol_error(text):
    inbound = Inbound(4096)
    try:
        inbound.check(text)
    except ProtocolError as exc:
        assert exc.code in {"bad_json", "invalid_message", "unknown_type", "unsupported_version", "bad_seq",
                            "too_large"}
