"""The participant's link (``server.game.link``): a connection is greeted with hello and state and replaces an older
one; each frame is answered (``pong``, the applied message's ``ack``, or a typed ``error`` with nothing applied);
frames of a replaced connection are ignored; a flood is refused and counted; a disconnect is logged."""

from __future__ import annotations

import asyncio
import json
from typing import Any

from steakhouse_live_parts import Events, Socket, closed, connection, opened

from server.game.budget import EventBudget
from server.game.connection import Connection
from server.game.link import MAX_LOGGED_ERRORS, ParticipantLink
from server.protocol.client import AnyClientMessage
from server.protocol.inbound import ProtocolError
from server.protocol.server import Ack


def frame(seq: int, type_: str = "focus", **fields: Any) -> str:
    return json.dumps({"v": 1, "seq": seq, "type": type_, **fields})


class Applied:
    """An ``apply`` that keeps the messages it was given (and refuses interrupts when told to)."""

    def __init__(self, refuse: bool = False) -> None:
        self.messages: list[AnyClientMessage] = []
        self.refuse = refuse

    def __call__(self, message: AnyClientMessage) -> Ack:
        if self.refuse:
            raise ProtocolError("queue_full", "full", message.seq)
        self.messages.append(message)
        return Ack(ack=message.seq, subtask=None, queued=0)


def replaced(link: ParticipantLink) -> tuple[tuple[Connection, Socket], tuple[Connection, Socket]]:
    """Open a connection on ``link``, then a newer one: both, with their sockets."""
    first = connection()
    opened(link, first[0])
    second = connection()
    opened(link, second[0])
    return first, second


def test_a_connection_is_greeted_and_a_newer_one_replaces_it() -> None:
    async def scenario() -> tuple[list[str], int | None, list[str], list[Any]]:
        events = Events()
        link = ParticipantLink(10_000, events)
        (first, first_socket), (second, second_socket) = replaced(link)
        await asyncio.wait_for(first.wait_closed(), 5)
        assert link.connection is second and link.connected.is_set()
        await closed(second, second_socket)
        return first_socket.types(), first_socket.closed_with, second_socket.types(), events.kept

    first, code, second, events = asyncio.run(scenario())
    assert first == ["hello", "state", "error"] and code == 4000, "the older window is told it was replaced"
    assert second == ["hello", "state"]
    assert events == [("connect", {"replaced": False, "resumed_at": 0}),
                      ("connect", {"replaced": True, "resumed_at": 0})]


def test_every_frame_is_answered_and_only_accepted_messages_are_applied() -> None:
    async def scenario() -> tuple[list[dict[str, Any]], list[int], list[str], bool]:
        events, applied = Events(), Applied()
        link = ParticipantLink(10_000, events, wall_ms=lambda: 123.0)
        conn, socket = connection()
        opened(link, conn)
        link.answered.clear()
        link.receive(conn, frame(1, "heartbeat", client_time=5.0), None, playing=True, apply=applied)
        answered = link.answered.is_set()
        link.receive(conn, frame(2, "focus"), None, playing=True, apply=applied)
        link.receive(conn, frame(2, "blur"), None, playing=True, apply=applied)  # seq not above the last accepted
        link.receive(conn, "{not json", None, playing=True, apply=applied)
        link.receive(conn, frame(3, "blur"), None, playing=False, apply=applied)
        await closed(conn, socket)
        return socket.sent[2:], [m.seq for m in applied.messages], events.kinds(), answered

    answers, applied, kinds, answered = asyncio.run(scenario())
    assert answers[0] == {**answers[0], "type": "pong", "ack": 1, "client_time": 5.0, "server_time": 123.0}
    assert answered, "a fast pilot trial steps once its participant answered"
    assert answers[1] == {**answers[1], "type": "ack", "ack": 2}
    assert [(a["type"], a.get("code")) for a in answers[2:]] == [
        ("error", "bad_seq"), ("error", "bad_json"), ("error", "not_playing")]
    assert applied == [2]
    assert kinds == ["connect", "error", "error", "error"]


def test_a_refusal_by_the_game_is_answered_as_an_error_and_nothing_is_accepted() -> None:
    async def scenario() -> tuple[list[dict[str, Any]], int]:
        link = ParticipantLink(10_000, Events())
        conn, socket = connection()
        opened(link, conn)
        link.receive(conn, frame(1, "interrupt", action="up"), None, playing=True, apply=Applied(refuse=True))
        last_seq = link.inbound.last_seq
        await closed(conn, socket)
        return socket.sent[2:], last_seq

    answers, last_seq = asyncio.run(scenario())
    assert [(a["type"], a["code"], a["ref"]) for a in answers] == [("error", "queue_full", 1)]
    assert last_seq == 0, "the refused message may be sent again with the same seq"


def test_frames_of_a_replaced_connection_are_ignored() -> None:
    async def scenario() -> list[int]:
        link, applied = ParticipantLink(10_000, Events()), Applied()
        (old, _), (new, _) = replaced(link)
        link.receive(old, frame(1), None, playing=True, apply=applied)
        link.receive(new, frame(1, "blur"), None, playing=True, apply=applied)
        return [m.seq for m in applied.messages]

    assert asyncio.run(scenario()) == [1]


def test_a_flood_is_refused_counted_and_stored_once_and_a_pilot_is_not_limited() -> None:
    async def scenario(limited: bool) -> tuple[list[str | None], list[Any]]:
        events = Events()
        link = ParticipantLink(10_000, events, limited=limited, budget=EventBudget(rate=1, burst=3, clock=lambda: 0.0))
        conn, socket = connection()
        opened(link, conn)  # takes one token
        for seq in range(1, 5):
            link.receive(conn, frame(seq, "blur"), None, playing=True, apply=Applied())
        link.receive(conn, frame(9, "heartbeat", client_time=1.0), None, playing=True, apply=Applied())
        link.drop(conn)
        await closed(conn, socket)
        return [a.get("code") or a["type"] for a in socket.sent[2:]], events.kept

    answers, events = asyncio.run(scenario(limited=True))
    assert answers == ["ack", "ack", "rate_limited", "rate_limited", "pong"], "heartbeats are never limited"
    assert [kind for kind, _ in events] == ["connect", "events_dropped", "disconnect", "events_dropped"]
    assert events[1][1] == {"dropped": 1, "by_kind": {"blur": 1}}
    assert events[3][1] == {"dropped": 1, "by_kind": {"blur": 1}}, "the rest is stored when they leave"
    pilot_answers, _ = asyncio.run(scenario(limited=False))
    assert pilot_answers == ["ack"] * 4 + ["pong"]


def test_rejections_are_logged_up_to_a_limit_but_always_answered() -> None:
    async def scenario() -> tuple[int, int]:
        events = Events()
        link = ParticipantLink(10_000, events, limited=False)
        conn, socket = connection()
        opened(link, conn)
        for _ in range(MAX_LOGGED_ERRORS + 5):
            link.receive(conn, "[]", None, playing=True, apply=Applied())
        await closed(conn, socket)
        return socket.types().count("error"), events.kinds().count("error")

    answered, logged = asyncio.run(scenario())
    assert (answered, logged) == (MAX_LOGGED_ERRORS + 5, MAX_LOGGED_ERRORS)


def test_dropping_the_connection_pauses_the_link_and_only_the_current_one_counts() -> None:
    async def scenario() -> tuple[bool, bool, bool, bool, list[str]]:
        events = Events()
        link = ParticipantLink(10_000, events)
        (old, _), (new, _) = replaced(link)
        link.wake.clear()
        stale = link.drop(old)
        current = link.drop(new)
        return stale, current, link.connected.is_set(), link.wake.is_set(), events.kinds()

    stale, current, connected, woken, kinds = asyncio.run(scenario())
    assert (stale, current, connected, woken) == (False, True, False, True)
    assert kinds == ["connect", "connect", "disconnect"]
