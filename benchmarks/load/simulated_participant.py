"""A simulated participant over the real participant API: join, consent, instructions, every trial over the
websocket, every questionnaire, then the completion page — and again as a new participant while time is left.

Choices follow the simulated human's rule (paper §IV-A, ``planner.human``): keep the current subtask until it
is done, then pick uniformly at random among the subtasks the server says the participant's modelled
knowledge makes available (``state.available``, computed from what this participant has seen). Like the
browser client it sends a heartbeat every second; the pong gives the message round trip. Everything received
can be kept (``capture``) so a test can check that no message leaves the participant's field of view.
"""

from __future__ import annotations

import asyncio
import json
import random
import time
from dataclasses import dataclass, field
from typing import Any

import httpx
from websockets.asyncio.client import ClientConnection, connect
from websockets.exceptions import ConnectionClosedOK

# One TLS context for every simulated participant: httpx otherwise loads the certificate bundle per client, CPU
# this benchmark would count against the server it measures.
TLS = httpx.create_ssl_context()
HEARTBEAT_S = 1.0


@dataclass
class Transcript:
    """One websocket connection: the trial it played and every message received, in order."""

    trial_id: int
    messages: list[dict[str, Any]] = field(default_factory=list)


@dataclass
class ClientStats:
    """What the simulated participants saw (the server's own numbers come from the store)."""

    joined: int = 0
    trials_played: int = 0
    trials_ended: int = 0
    questionnaires: int = 0
    completed: int = 0
    messages: int = 0
    late_messages: int = 0
    """Choices that crossed the trial's end on the wire (answered ``not_playing``; a race, not a fault)."""
    pong_rtt_ms: list[float] = field(default_factory=list)
    ack_rtt_ms: list[float] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)
    waiting_messages: int = 0
    """``waiting`` messages: the server was full and the participant waited for a slot."""
    turned_away: int = 0
    """``server_full``: waited past the server's limit and screened out."""
    transcripts: list[Transcript] = field(default_factory=list)


class SimulatedParticipant:
    def __init__(self, base_url: str, study_id: str, rng: random.Random, stats: ClientStats, *,
                 deadline: float, name: str, capture: bool = False) -> None:
        self.base, self.study_id, self.rng, self.stats = base_url, study_id, rng, stats
        self.deadline, self.name, self.capture = deadline, name, capture
        self.http = httpx.AsyncClient(base_url=base_url, timeout=30, verify=TLS)
        self.token = ""

    async def close(self) -> None:
        await self.http.aclose()

    def time_left(self) -> float:
        return self.deadline - time.monotonic()

    async def call(self, method: str, path: str, body: Any = None) -> dict[str, Any]:
        headers = {"Authorization": f"Bearer {self.token}"} if self.token else {}
        response = await self.http.request(method, path, json=body, headers=headers)
        if response.status_code >= 400:
            raise RuntimeError(f"{method} {path}: {response.status_code} {response.text[:200]}")
        answer: dict[str, Any] = response.json()
        return answer

    async def run(self) -> None:
        """Take one participant from the landing page to the end (or until the deadline)."""
        joined = await self.call("POST", f"/api/studies/{self.study_id}/join",
                                 {"recruiting": {"PROLIFIC_PID": self.name, "STUDY_ID": "load"}})
        self.token = joined["token"]
        self.stats.joined += 1
        view = await self.call("POST", "/api/session/consent", {"accept": True})
        view = await self.call("POST", "/api/session/instructions_done")
        while self.time_left() > 0:
            state = view["state"]
            if state in ("practice", "trial"):
                if not await self.play():
                    return
            elif state == "questionnaire":
                await self.answer(view["questionnaire"])
            elif state in ("done", "screened_out"):
                await self.call("GET", "/api/session/completion")
                self.stats.completed += 1
                return
            else:
                raise RuntimeError(f"unexpected session state {state!r}")
            view = await self.call("GET", "/api/session")

    async def answer(self, questionnaire: dict[str, Any]) -> None:
        answers = {item["id"]: self.rng.randint(item["scale"]["min"], item["scale"]["max"])
                   for item in questionnaire["items"]}
        await self.call("POST", "/api/session/questionnaire", {"questionnaire_id": questionnaire["id"],
                                                               "answers": answers})
        self.stats.questionnaires += 1

    async def play(self) -> bool:
        """Play the current trial until ``trial_end`` (True) or the deadline (False: the socket is closed)."""
        url = self.base.replace("http", "ws", 1) + f"/ws/play?token={self.token}"
        async with connect(url, max_size=1 << 22) as ws:
            return await Game(ws, self).play()


class Game:
    """One websocket connection: numbered sends, heartbeats, subtask choices, round-trip timing."""

    def __init__(self, ws: ClientConnection, participant: SimulatedParticipant) -> None:
        self.ws, self.p, self.stats = ws, participant, participant.stats
        self.seq = 0
        self.sent_at: dict[int, float] = {}
        self.transcript: Transcript | None = None

    async def send(self, type_: str, **fields: Any) -> int:
        """Send a message. When the server has just closed the socket (it ends a trial with ``trial_end`` and a
        normal close) the message is dropped: what the server sent before closing is still to be read, and
        :meth:`play` reads it (a heartbeat due at that moment is not a failure of the trial)."""
        self.seq += 1
        self.sent_at[self.seq] = time.monotonic()
        try:
            await self.ws.send(json.dumps({"v": 1, "seq": self.seq, "type": type_, **fields}))
        except ConnectionClosedOK:
            self.sent_at.pop(self.seq, None)
        return self.seq

    async def play(self) -> bool:
        next_beat = time.monotonic() + HEARTBEAT_S
        while True:
            left = self.p.time_left()
            if left <= 0:
                return False
            try:
                raw = await asyncio.wait_for(self.ws.recv(), min(left, max(next_beat - time.monotonic(), 0.01)))
            except TimeoutError:
                raw = None
            if time.monotonic() >= next_beat:
                await self.send("heartbeat", client_time=time.monotonic() * 1000)
                next_beat += HEARTBEAT_S
            if raw is None:
                continue
            message: dict[str, Any] = json.loads(raw)
            if await self.on_message(message):
                return True

    async def on_message(self, message: dict[str, Any]) -> bool:
        """Handle one server message; True when the trial has ended."""
        self.stats.messages += 1
        kind = message["type"]
        if kind == "hello":
            self.stats.trials_played += 1
            if self.p.capture:
                self.transcript = Transcript(message["trial"]["id"])
                self.stats.transcripts.append(self.transcript)
        if self.transcript is not None:
            self.transcript.messages.append(message)
        if kind == "state":
            await self.choose(message)
        elif kind == "ack":
            self.rtt(message["ack"], self.stats.ack_rtt_ms)
        elif kind == "pong":
            self.sent_at.pop(message["ack"], None)
            self.stats.pong_rtt_ms.append(time.monotonic() * 1000 - message["client_time"])
        elif kind == "waiting":
            self.stats.waiting_messages += 1
        elif kind == "error" and message["code"] == "not_playing":
            self.stats.late_messages += 1
        elif kind == "error" and message["code"] == "server_full":
            self.stats.turned_away += 1
            return True
        elif kind == "error":
            self.stats.errors.append(f"{self.p.name}: error {message['code']}: {message['message'][:120]}")
        elif kind == "trial_end":
            self.stats.trials_ended += 1
            return True
        return False

    def rtt(self, seq: int, into: list[float]) -> None:
        sent = self.sent_at.pop(seq, None)
        if sent is not None:
            into.append((time.monotonic() - sent) * 1000)

    async def choose(self, state: dict[str, Any]) -> None:
        hud = state["hud"]
        over = hud["orders_left"] == 0 or hud["ticks_left"] == 0
        if state["subtask"] is None and state["available"] and not over:
            await self.send("select_subtask", subtask=self.p.rng.choice(state["available"]))


async def keep_participating(base_url: str, study_id: str, index: int, seed: int, stats: ClientStats, *,
                             deadline: float, start_after: float = 0.0, capture: bool = False) -> None:
    """One seat of the load: simulated participants one after another until the deadline. Failures are
    counted in ``stats.errors`` (the seat then takes a new participant)."""
    await asyncio.sleep(start_after)
    rng = random.Random(seed * 1_000_003 + index)
    number = 0
    while time.monotonic() < deadline:
        number += 1
        participant = SimulatedParticipant(base_url, study_id, rng, stats, deadline=deadline,
                                           name=f"load-{seed}-{index}-{number}", capture=capture)
        try:
            await participant.run()
        except (OSError, RuntimeError, httpx.HTTPError, KeyError, ValueError) as exc:
            stats.errors.append(f"seat {index}: {type(exc).__name__}: {str(exc)[:200]}")
            await asyncio.sleep(0.5)
        except Exception as exc:
            if time.monotonic() < deadline:
                stats.errors.append(f"seat {index}: {type(exc).__name__}: {str(exc)[:200]}")
                await asyncio.sleep(0.5)
        finally:
            await participant.close()


async def run_load(base_url: str, study_id: str, participants: int, seconds: float, *, seed: int = 0,
                   ramp_s: float = 0.0, capture: bool = False) -> ClientStats:
    """``participants`` seats playing for ``seconds`` (their starts spread over ``ramp_s``); bounded in time."""
    stats = ClientStats()
    deadline = time.monotonic() + seconds
    seats = [keep_participating(base_url, study_id, i, seed, stats, deadline=deadline,
                                start_after=ramp_s * i / max(participants, 1), capture=capture)
             for i in range(participants)]
    try:
        await asyncio.wait_for(asyncio.gather(*seats), seconds + 30)
    except TimeoutError:
        stats.errors.append("the load did not stop within 30 s of its deadline")
    return stats
