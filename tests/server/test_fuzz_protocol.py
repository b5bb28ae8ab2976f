"""Property-based fuzzing of the websocket protocol (docs/protocol.md §2), interleaved with real play.

Thousands of generated frames — valid messages, valid messages with one field broken (version, sequence
number, type, a field's type or value, an extra or a missing field), arbitrary JSON, arbitrary text, binary
frames, oversized and deeply nested frames — are sent one at a time into live trials while a scripted
participant keeps choosing subtasks on the same connection. The properties:

- every frame gets exactly one reply, in order: ``ack`` / ``pong`` (with its ``seq``) when it is valid and
  new (or ``rate_limited`` once the trial's event budget is spent: a script sends far faster than a person,
  ``server/game/budget.py``), else an ``error`` with a documented code and the rejected ``seq`` as ``ref`` when
  it could be read;
- every server message is a well-formed protocol message, numbered 1, 2, 3, … on its connection;
- the game never crashes (no ``internal`` error, the loop task alive) and keeps advancing.
"""

from __future__ import annotations

import asyncio
import json
import math
from dataclasses import dataclass
from typing import Any

import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st
from steakhouse_testing import Player

from planner.subtasks import SUBTASKS
from server.protocol.interrupts import Interrupt
from server.protocol.server import server_adapter
from store.tables import EventRow

pytestmark = pytest.mark.store_agnostic

CODES = {"bad_frame", "too_large", "bad_json", "invalid_message", "unknown_type", "unsupported_version",
         "bad_seq", "queue_full", "not_playing", "rate_limited"}
LIMIT = 4096
FRAMES = 250
EXAMPLES = 8
BURST = 800
SUBTASK_NAMES = [s.value for s in SUBTASKS]
ACTIONS = [i.value for i in Interrupt]
ANY = frozenset(CODES | {"accept"})
# Each example drives a live trial for seconds: shrinking would take minutes. A failure names its frame.
NO_SHRINK = (Phase.explicit, Phase.generate)


@dataclass(frozen=True)
class Frame:
    """A frame to send and what may come back: ``"accept"`` and/or error codes."""

    data: str | bytes
    expect: frozenset[str]


@dataclass(frozen=True, repr=False)
class Recipe:
    """A generated frame whose ``seq`` is filled in at sending time (relative to the last accepted one), so
    what Hypothesis draws never depends on the server: ``fresh`` = last + ``offset``, ``old`` = a number
    already used (last − ``offset``), ``None`` = as drawn."""

    expect: frozenset[str]
    message: dict[str, Any] | None = None
    raw: str | bytes | None = None
    seq: str | None = None
    offset: int = 1

    def __repr__(self) -> str:
        shown = repr(self.message if self.message is not None else self.raw)
        return f"Recipe({shown[:60]}{'…' if len(shown) > 60 else ''}, seq={self.seq})"

    def frame(self, last_seq: int) -> Frame:
        if self.message is None:
            assert self.raw is not None
            return Frame(self.raw, self.expect)
        message, expect = dict(self.message), self.expect
        if self.seq == "fresh":
            message["seq"] = last_seq + self.offset
        elif self.seq == "old":
            message["seq"] = max(last_seq - self.offset, 1) if last_seq >= 1 else 0
            expect = frozenset({"bad_seq"}) if last_seq >= 1 else frozenset({"invalid_message"})
        return Frame(json.dumps(message), expect)


json_leaf = st.one_of(st.none(), st.booleans(), st.integers(-2**70, 2**70),
                      st.floats(allow_nan=False, allow_infinity=False), st.text(max_size=20))
json_value = st.recursive(json_leaf, lambda inner: st.one_of(
    st.lists(inner, max_size=5), st.dictionaries(st.text(max_size=10), inner, max_size=5)), max_leaves=20)
wrong_for_string = st.one_of(st.none(), st.booleans(), st.integers(), st.floats(allow_nan=False),
                             st.lists(st.text(max_size=3), max_size=2), st.text(max_size=30))


def valid_body(draw: st.DrawFn) -> dict[str, Any]:
    kind = draw(st.sampled_from(["select_subtask", "interrupt", "heartbeat", "focus", "blur", "idle"]))
    body: dict[str, Any] = {"type": kind}
    if kind == "select_subtask":
        body["subtask"] = draw(st.sampled_from(SUBTASK_NAMES))
    elif kind == "interrupt":
        body["action"] = draw(st.sampled_from(ACTIONS))
    elif kind == "heartbeat":
        body["client_time"] = draw(st.one_of(st.floats(allow_nan=False, allow_infinity=False, width=64),
                                             st.integers(0, 2**52)))
    elif kind == "idle":
        body["idle_ms"] = draw(st.integers(0, 2**40))
    return body


def field_breakage(draw: st.DrawFn, body: dict[str, Any]) -> dict[str, Any]:
    """The body with one field given a wrong value, or an extra field, or a required field removed."""
    body = dict(body)
    fields = [k for k in body if k != "type"]
    how = draw(st.sampled_from(["value", "extra", "missing"] if fields else ["extra"]))
    if how == "extra":
        body[draw(st.text(min_size=1, max_size=12).filter(lambda k: k not in ("v", "seq", "type", *body)))] = \
            draw(json_value)
    elif how == "missing":
        del body[draw(st.sampled_from(fields))]
    else:
        name = draw(st.sampled_from(fields))
        if name in ("subtask", "action"):
            known = SUBTASK_NAMES if name == "subtask" else ACTIONS
            body[name] = draw(wrong_for_string.filter(lambda v: v not in known))
        elif name == "client_time":
            body[name] = draw(st.one_of(st.none(), st.booleans(), st.text(max_size=8),
                                        st.lists(st.integers(), max_size=2)))
        else:
            body[name] = draw(st.one_of(st.integers(max_value=-1), st.floats(allow_nan=False), st.booleans(),
                                        st.none(), st.text(max_size=8).map(str)))
    return body


@st.composite
def recipes(draw: st.DrawFn) -> Recipe:
    """One frame: mostly valid messages, else one of many ways to be wrong."""
    gap = draw(st.integers(1, 3))
    kind = draw(st.sampled_from(["valid"] * 4 + ["field", "version", "seq", "old_seq", "type", "json", "text",
                                                 "binary", "large", "nested", "float_time"]))
    if kind in ("valid", "field", "version", "type", "float_time"):
        body = valid_body(draw)
        expect = frozenset({"accept"})
        if kind == "field":
            body = field_breakage(draw, body)
            expect = frozenset({"invalid_message"})
        elif kind == "type":
            body["type"] = draw(wrong_for_string.filter(lambda t: t not in ("select_subtask", "interrupt",
                                                                            "heartbeat", "focus", "blur", "idle")))
            expect = frozenset({"unknown_type"})
        elif kind == "float_time":
            value = draw(st.sampled_from([math.inf, -math.inf, math.nan, 1e308, -0.0, 5e-324]))
            body = {"type": "heartbeat", "client_time": value}
            expect = frozenset({"accept"} if math.isfinite(value) else {"invalid_message"})
        message: dict[str, Any] = {"v": 1, **body}
        if kind == "version":
            bad = draw(st.one_of(st.sampled_from([0, 2, -1, "1", True, None, [1], 1.5]), json_value)
                       .filter(lambda v: v != 1 or isinstance(v, bool)))
            if draw(st.booleans()):
                message["v"] = bad
            else:
                del message["v"]
            expect = frozenset({"unsupported_version"})
        if kind in ("valid", "float_time") and body["type"] == "interrupt":
            expect = expect | {"queue_full"}
        return Recipe(expect, message, seq="fresh", offset=gap)
    if kind == "old_seq":
        return Recipe(frozenset({"bad_seq"}), {"v": 1, **valid_body(draw)}, seq="old", offset=draw(st.integers(0, 5)))
    if kind == "seq":
        message = {"v": 1, **valid_body(draw)}
        if draw(st.integers(0, 9)) > 0:
            message["seq"] = draw(st.one_of(
                st.sampled_from([0, -1, True, False, None, "5", 5.0, 2**53 + 1, [1], {}]), st.text(max_size=5),
                st.floats(allow_nan=False, allow_infinity=False)))
        return Recipe(frozenset({"invalid_message"}), message)
    if kind == "json":
        document = draw(json_value)
        return Recipe(ANY if isinstance(document, dict) else frozenset({"invalid_message"}), raw=json.dumps(document))
    if kind == "text":
        return Recipe(ANY, raw=draw(st.text(max_size=200)))
    if kind == "binary":
        return Recipe(frozenset({"bad_frame"}), raw=draw(st.binary(max_size=200)))
    if kind == "large":
        size = draw(st.integers(LIMIT + 1, 3 * LIMIT))
        return Recipe(frozenset({"too_large"}), {"v": 1, "type": "idle", "idle_ms": 1, "pad": "é" * (size // 2)},
                      seq="fresh")
    depth = draw(st.integers(500, 2000))
    return Recipe(frozenset({"bad_json", "too_large", "invalid_message"}), raw="[" * depth + "]" * depth)


def expected_ref(frame: Frame) -> int | None:
    """The ``ref`` of an error: the frame's ``seq`` when it could be read (docs/protocol.md)."""
    if isinstance(frame.data, bytes) or len(frame.data.encode("utf-8", "surrogatepass")) > LIMIT:
        return None
    try:
        value = json.loads(frame.data)
    except (ValueError, RecursionError):
        return None
    seq = value.get("seq") if isinstance(value, dict) else None
    ok = isinstance(seq, int) and not isinstance(seq, bool) and 1 <= seq <= 2**53
    return seq if ok else None


class Session:
    """One fuzzed connection: sends frames one at a time, checks each reply, plays on the side."""

    def __init__(self, sock: Any) -> None:
        self.sock = sock
        self.last_seq = 0
        self.server_seq = 0
        self.state: dict[str, Any] | None = None
        self.first_tick: int | None = None
        self.ended = False
        self.sent = 0

    async def next_message(self) -> dict[str, Any]:
        message: dict[str, Any] = await self.sock.recv()
        server_adapter.validate_python(message)
        self.server_seq += 1
        assert message["seq"] == self.server_seq, f"server seq gap: {message}"
        if message["type"] == "state":
            self.state = message
            self.first_tick = message["tick"] if self.first_tick is None else self.first_tick
        elif message["type"] == "trial_end":
            self.ended = True
        return message

    async def exchange(self, frame: Frame) -> None:
        await self.sock.send_raw(frame.data)
        self.sent += 1
        while True:
            reply = await self.next_message()
            if reply["type"] in ("ack", "pong", "error"):
                break
        where = f"frame {frame.data[:120]!r} → {reply}"
        if reply["type"] == "error":
            assert reply["code"] in CODES, where
            allowed = frame.expect | ({"not_playing"} if self.ended else set()) | (
                {"rate_limited"} if "accept" in frame.expect else set())
            assert reply["code"] in allowed, where
            assert reply["ref"] == expected_ref(frame), where
            return
        assert "accept" in frame.expect, where
        assert reply["ack"] == expected_ref(frame) and reply["ack"] > self.last_seq, where
        self.last_seq = reply["ack"]

    def play_frame(self) -> Frame | None:
        """A real participant's choice when the avatar is idle (like the scripted player)."""
        state = self.state
        if state is None or state["subtask"] is not None or not state["available"] or self.ended:
            return None
        self.state = None
        message = {"v": 1, "seq": self.last_seq + 1, "type": "select_subtask", "subtask": state["available"][0]}
        return Frame(json.dumps(message), frozenset({"accept"}))


def study(study_file: Any) -> Any:
    return study_file(world={"orders": 20, "horizon": 3000, "kb_delay": 1})


def assert_no_crash(server: Any, trial_ids: list[int]) -> None:
    games = server.services.registry.games
    for trial_id in trial_ids:
        game = games.get(trial_id)
        if game is not None and game.task is not None and game.task.done():
            assert game.task.cancelled() or game.task.exception() is None, f"trial {trial_id} loop crashed"
    with server.services.store.transaction() as session:
        errors = [e.payload for e in session.query(EventRow).filter(EventRow.kind == "error")]
    assert not [p for p in errors if p.get("code") in ("internal", "robot")], errors


def test_fuzzed_frames_interleaved_with_play_each_get_one_typed_reply(live_server, study_file):
    server = live_server([study(study_file)], pings=False, join_rate_per_minute=0)
    trial_ids: list[int] = []
    sent: list[int] = []

    @settings(max_examples=EXAMPLES, deadline=None, database=None, phases=NO_SHRINK,
              suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow,
                                     HealthCheck.data_too_large, HealthCheck.large_base_example])
    @given(data=st.data())
    def fuzz(data: st.DataObject) -> None:
        async def scenario() -> None:
            player = Player(server.url)
            await player.ready()
            sock = await player.socket()
            try:
                session = Session(sock)
                hello = await session.next_message()
                trial_ids.append(hello["trial"]["id"])
                await session.next_message()
                for _ in range(FRAMES):
                    recipe = data.draw(recipes())
                    played = session.play_frame()
                    if played is not None:
                        await session.exchange(played)
                    await session.exchange(recipe.frame(session.last_seq))
                first = session.first_tick or 0
                while not session.ended and (session.state is None or session.state["tick"] < first + 3):
                    await session.next_message()
                sent.append(session.sent)
            finally:
                await sock.close()
                await player.close()

        asyncio.run(scenario())

    fuzz()
    assert len(trial_ids) >= EXAMPLES and sum(sent) >= EXAMPLES * FRAMES
    assert_no_crash(server, trial_ids)


@settings(max_examples=1, deadline=None, database=None, phases=NO_SHRINK,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.data_too_large,
                                 HealthCheck.large_base_example, HealthCheck.too_slow])
@given(data=st.data())
def test_a_burst_of_fuzzed_frames_without_waiting_is_answered_frame_for_frame(live_server, study_file, data):
    burst = [data.draw(recipes()) for _ in range(BURST)]
    server = live_server([study(study_file)], pings=False, join_rate_per_minute=0)

    async def scenario() -> tuple[list[dict[str, Any]], dict[str, Any], dict[str, Any]]:
        player = Player(server.url)
        await player.ready()
        sock = await player.socket()
        try:
            await sock.recv()
            first = await sock.recv()
            for i, recipe in enumerate(burst):
                await sock.send_raw(recipe.frame(i).data)
            replies: list[dict[str, Any]] = []
            while len(replies) < len(burst):
                message = await sock.recv()
                server_adapter.validate_python(message)
                if message["type"] in ("ack", "pong", "error"):
                    replies.append(message)
            later = await sock.until(lambda m: m["type"] == "state" and m["tick"] > first["tick"] + 3)
        finally:
            await sock.close()
            await player.close()
        return replies, first, later

    replies, first, later = asyncio.run(scenario())
    assert all(r["type"] != "error" or r["code"] in CODES for r in replies)
    assert later["tick"] > first["tick"]
    assert_no_crash(server, list(server.services.registry.games))
