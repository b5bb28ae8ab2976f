"""One simulated participant over the participant flow a browser uses (docs/protocol.md): join with recruiting
ids (as a pilot, with the admin token), consent, instructions, the quiz when the study has one, the practice,
every round over the game websocket, every questionnaire, the end page.

On the websocket it answers every ``state`` frame with exactly one message (a choice, an interrupt or a
heartbeat; :mod:`pilot.mind`): at the pilot's ``fast`` pace the server steps as soon as that answer and the
robot's decision are in. At the ``realtime`` pace it thinks before each choice of a next task, for a
wall-clock time drawn uniformly from ``think_seconds_min``..``think_seconds_max`` (:mod:`pilot.config`): it goes
on perceiving the frames that arrive meanwhile (under ``fixed_rate`` the world goes on; under
``wait_for_participant`` none arrive) and then chooses from what it knows at that moment. It reads nothing but
the frames (``hello``, ``state``, ``blocked``, ``nudge``, ``trial_end``).

A seat with a :class:`~pilot.scripts.Script` plays every round by that script instead (a participant gaming the
engagement rules: a held key, a tapped key, a random task every few seconds, one key per round), on the wall clock.
"""

from __future__ import annotations

import asyncio
import contextlib
import functools
import json
import ssl
from collections.abc import Awaitable, Callable
from dataclasses import dataclass, field
from typing import Any

import httpx
import numpy as np
from websockets.asyncio.client import connect
from websockets.exceptions import ConnectionClosed

from pilot.answers import answer
from pilot.config import ParticipantConfig
from pilot.mind import STAY, WAIT_REASONS, Mind, decide, faced_station_working, read_refusal
from pilot.perception import Perception
from pilot.scripts import Script
from planner.subtasks import Subtask
from study_config.catalog import LoadedStudy


@functools.cache
def tls_context() -> ssl.SSLContext:
    """One TLS context for every simulated participant, httpx's default one (its certificate bundle, the
    ``SSL_CERT_FILE`` / ``SSL_CERT_DIR`` it honours): httpx builds a new one per client otherwise, loading the bundle
    each time (tens of milliseconds of CPU per participant)."""
    return httpx.create_ssl_context()


ANSWERS_STREAM = 2**31
"""The generator stream of a participant's questionnaire and quiz answers (trials use 0, 1, 2, …)."""


def trial_rng(seed: tuple[int, ...], trial: int) -> np.random.Generator:
    """The generator of a participant's ``trial``-th trial (0-based, practice included)."""
    return np.random.default_rng([*seed, trial])


def respond(mind: Mind, seen: Perception, message: dict[str, Any], needs: dict[str, str], loaded: LoadedStudy,
            config: ParticipantConfig, rng: np.random.Generator, angle: float | None = None
            ) -> tuple[Perception, Mind, dict[str, Any]]:
    """One ``state`` frame in, the knowledge, mind and message body (without ``v`` / ``seq``) out: everything
    the simulated participant does with a frame, and all it uses (besides the study file and its config).
    ``angle`` is the trial's field of view (``hello.fov_angle``; the study's ``world.fov_angle`` without it)."""
    world = loaded.study.world
    seen = seen.observe(message, angle if angle is not None else world.fov_angle, world.kb_delay)
    reply, mind = decide(mind, seen, message, needs, loaded.rules, config, rng)
    body = reply.body()
    if body["type"] == "heartbeat":
        body["client_time"] = 0
    return seen, mind, body


class PilotFlowError(RuntimeError):
    """The server answered the simulated participant with an error it cannot go on from."""


class TrialNotStarted(PilotFlowError):
    """The server could not start the trial (it says to try again later)."""


RETRIES = 3
RETRY_WAIT_S = 2.0


@dataclass
class Outcome:
    """What one simulated participant did (the store holds the rest)."""

    name: str
    participant_id: str = ""
    trials: int = 0
    interrupts: int = 0
    selections: int = 0
    questionnaires: int = 0
    completed: bool = False
    frames: list[list[dict[str, Any]]] = field(default_factory=list)
    """Per trial, every websocket message received, when kept (``keep_frames``)."""
    sent: list[list[dict[str, Any]]] = field(default_factory=list)
    """Per trial, every message sent, when kept (``keep_frames``)."""


@dataclass(frozen=True)
class Seat:
    """Where and how a simulated participant plays."""

    base_url: str
    admin_token: str
    loaded: LoadedStudy
    config: ParticipantConfig
    pace: str = "fast"
    keep_frames: bool = False
    script: Script | None = None
    """Play every round by this script (a participant gaming the rules) instead of the simulated participant."""
    sleep: Callable[[float], Awaitable[None]] = asyncio.sleep
    """How its wall-clock waits pass (think time, key taps, a script's pace): tests pass one that moves the server's
    injected clock."""


class SimulatedParticipant:
    def __init__(self, seat: Seat, name: str, seed: tuple[int, ...],
                 on_trial: Callable[[int], None] = lambda delta: None) -> None:
        """``seed``: the participant's seed key; trial k plays with ``default_rng([*seed, k])`` (see
        :func:`trial_rng`), its answers and quiz come from ``default_rng([*seed, -1])``."""
        self.seat, self.seed, self.on_trial = seat, seed, on_trial
        self.rng = np.random.default_rng([*seed, ANSWERS_STREAM])
        self.played = 0
        self.outcome = Outcome(name)
        self.token = ""
        self.gap_mean = 0.0
        study = seat.loaded.study
        self.reversed = {i.id for q in study.questionnaires for i in q.items if getattr(i, "reverse", False)}

    async def call(self, http: httpx.AsyncClient, method: str, path: str, body: Any = None,
                   token: str | None = None) -> dict[str, Any]:
        headers = {"Authorization": f"Bearer {token or self.token}"}
        response = await http.request(method, path, json=body, headers=headers)
        if response.status_code >= 400:
            raise PilotFlowError(f"{method} {path}: {response.status_code} {response.text[:300]}")
        out: dict[str, Any] = response.json()
        return out

    async def run(self) -> Outcome:
        study = self.seat.loaded.study
        first = study.recruiting.url_parameters[0] if study.recruiting.url_parameters else "PROLIFIC_PID"
        async with httpx.AsyncClient(base_url=self.seat.base_url, timeout=60, verify=tls_context()) as http:
            joined = await self.call(http, "POST", f"/api/studies/{study.id}/join",
                                     {"recruiting": {first: self.outcome.name}, "pilot": {"pace": self.seat.pace}},
                                     token=self.seat.admin_token)
            self.token = joined["token"]
            self.outcome.participant_id = joined["participant_id"]
            view = await self.call(http, "GET", "/api/session")
            while True:
                state = view["state"]
                if state == "consent":
                    view = await self.call(http, "POST", "/api/session/consent", {"accept": True})
                elif state == "instructions":
                    view = await self.call(http, "POST", "/api/session/instructions_done")
                elif state == "quiz":
                    view = await self.call(http, "POST", "/api/session/quiz", {"answers": self.quiz_answers()})
                elif state in ("practice", "trial"):
                    await self.play_with_retries()
                    view = await self.call(http, "GET", "/api/session")
                elif state == "questionnaire":
                    answers = answer(view["questionnaire"], self.gap_mean, self.seat.config, self.reversed, self.rng)
                    view = await self.call(http, "POST", "/api/session/questionnaire",
                                           {"questionnaire_id": view["questionnaire"]["id"], "answers": answers})
                    self.outcome.questionnaires += 1
                elif state in ("done", "screened_out"):
                    await self.call(http, "GET", "/api/session/completion")
                    self.outcome.completed = state == "done"
                    return self.outcome
                else:
                    raise PilotFlowError(f"unexpected session state {state!r}")

    def quiz_answers(self) -> dict[str, int]:
        quiz = self.seat.loaded.study.quiz
        if quiz is None:
            return {}
        out = {}
        for q in quiz.questions:
            wrong = [i for i in range(len(q.options)) if i != q.correct]
            slip = wrong and self.rng.random() < self.seat.config.quiz_error_rate
            out[q.id] = int(self.rng.choice(wrong)) if slip else q.correct
        return out

    async def play_with_retries(self) -> None:
        """Play the current trial; a trial the server could not start (``internal``: e.g. its robot planner did
        not open in time on a busy machine) is tried again, as a browser reconnects."""
        for attempt in range(RETRIES + 1):
            try:
                await self.play()
                return
            except TrialNotStarted:
                if attempt == RETRIES:
                    raise
                await asyncio.sleep(RETRY_WAIT_S * (attempt + 1))

    async def play(self) -> None:
        """One trial: answer every ``state`` until ``trial_end``."""
        loaded, config = self.seat.loaded, self.seat.config
        realtime = self.seat.pace == "realtime"
        if realtime:
            config = config.model_copy(update={"decision_latency_ticks": 0})
        rng = trial_rng(self.seed, self.played)
        self.played += 1
        received: list[dict[str, Any]] = []
        sent: list[dict[str, Any]] = []
        if self.seat.keep_frames:
            self.outcome.frames.append(received)
            self.outcome.sent.append(sent)
        url = self.seat.base_url.replace("http", "ws", 1) + "/ws/play"
        seq = 0
        mind = Mind()
        seen: Perception | None = None
        needs: dict[str, str] = {}
        angle = loaded.study.world.fov_angle
        latest: dict[str, Any] = {}
        thinking: asyncio.Task[None] | None = None
        paper_clock = False
        self.on_trial(1)

        async def send(ws: Any, body: dict[str, Any]) -> None:
            nonlocal seq
            seq += 1
            if self.seat.keep_frames:
                sent.append(body)
            self.outcome.interrupts += body["type"] == "interrupt"
            self.outcome.selections += body["type"] == "select_subtask"
            with contextlib.suppress(ConnectionClosed):  # the trial ended meanwhile: its trial_end is still to come
                await ws.send(json.dumps({"v": 1, "seq": seq, **body}))

        def think_time() -> float:
            return float(rng.uniform(config.think_seconds_min, config.think_seconds_max))

        async def wait_then_choose(ws: Any) -> None:
            """The paper's clock, a task refused while its station works: press stay while the faced station is at
            work (at most ``wait_taps`` times), then think and choose again."""
            pressed_at: int | None = None
            for _ in range(config.wait_taps):
                await self.seat.sleep(config.wait_tap_seconds)
                if not latest or not faced_station_working(latest):
                    break
                if latest["tick"] == pressed_at:
                    continue  # the last press has not moved the kitchen yet: a person watches for it
                pressed_at = int(latest["tick"])
                await send(ws, STAY.body())
            await think_then_choose(ws, think_time())

        async def think_then_choose(ws: Any, seconds: float) -> None:
            """Wait ``seconds`` of wall-clock time, then choose from the latest frame and what it knows now."""
            nonlocal mind
            await self.seat.sleep(seconds)
            assert seen is not None
            reply, mind = decide(mind, seen, latest, needs, loaded.rules, config, rng)
            if reply.type != "heartbeat":
                await send(ws, reply.body())

        try:
            async with connect(url, subprotocols=["steakhouse.v1", f"token.{self.token}"],  # type: ignore[list-item]
                               max_size=1 << 22) as ws:
                if self.seat.script is not None:
                    await self.play_script(ws, self.seat.script, rng, send, received)
                    return
                async for raw in ws:
                    message: dict[str, Any] = json.loads(raw)
                    if self.seat.keep_frames:
                        received.append(message)
                    kind = message["type"]
                    if kind == "hello":
                        paper_clock = message["mode"] == "wait_for_participant"
                        needs = dict(message["needs"])
                        angle = float(message["fov_angle"])  # the trial's: a level when the angle is a factor
                        seen = Perception(message["width"], message["height"],
                                          tuple(loaded.layouts.values()))
                    elif kind == "state" and seen is not None:
                        latest = message
                        if thinking is not None and not thinking.done():
                            seen = seen.observe(message, angle, loaded.study.world.kb_delay)
                            continue
                        if realtime and message["subtask"] is None:
                            seen = seen.observe(message, angle, loaded.study.world.kb_delay)
                            thinking = asyncio.create_task(think_then_choose(ws, think_time()))
                            continue
                        seen, mind, body = respond(mind, seen, message, needs, loaded, config, rng, angle)
                        await send(ws, body)
                    elif kind == "blocked" and message["ended"] and message["subtask"] and seen is not None:
                        waits = realtime and paper_clock and message["reason"] in WAIT_REASONS
                        mind = read_refusal(mind, seen, Subtask(message["subtask"]), message["reason"],
                                            loaded.rules, waits=waits)
                        if waits and (thinking is None or thinking.done()):
                            thinking = asyncio.create_task(wait_then_choose(ws))
                    elif (kind == "ack" and realtime and message["subtask"] is None and not message["queued"]
                          and latest and (thinking is None or thinking.done())):
                        # Stopped, or a choice refused: under wait_for_participant no frame comes until it acts.
                        latest = {**latest, "subtask": None}
                        thinking = asyncio.create_task(think_then_choose(ws, think_time()))
                    elif kind == "error" and message["code"] == "internal" and seen is None:
                        raise TrialNotStarted(message["message"])
                    elif kind == "error" and message["code"] not in ("not_playing", "queue_full"):
                        # queue_full: its "." presses outran a loaded server's steps; the page only notes it.
                        raise PilotFlowError(f"websocket error {message['code']}: {message['message']}")
                    elif kind == "trial_end":
                        self.outcome.trials += 1
                        break
        finally:
            if thinking is not None:
                thinking.cancel()
            self.on_trial(-1)
        self.gap_mean = seen.gap_mean if seen is not None else 0.0

    async def play_script(self, ws: Any, script: Script, rng: np.random.Generator,
                          send: Callable[[Any, dict[str, Any]], Any], received: list[dict[str, Any]]) -> None:
        """One round by ``script``: its messages on the wall clock, as the browser would send them, until
        ``trial_end``. Refusals the browser only shows (a full key queue, too many messages) are ignored."""
        needs: dict[str, str] = {}
        held: str | None = None
        pacer: asyncio.Task[None] | None = None

        async def pace(mode: str, rate: float) -> None:
            sent = 0
            while (delay := script.delay(mode, rate, sent)) is not None:
                await self.seat.sleep(delay)
                await send(ws, script.send(held, needs, rng))
                sent += 1

        try:
            async for raw in ws:
                message: dict[str, Any] = json.loads(raw)
                if self.seat.keep_frames:
                    received.append(message)
                kind = message["type"]
                if kind == "hello":
                    needs = dict(message["needs"])
                    if pacer is None:
                        pacer = asyncio.create_task(pace(message["mode"], float(message["tick_rate_hz"])))
                elif kind == "state":
                    held = message["you"]["held"]
                elif kind == "error" and message["code"] == "internal" and pacer is None:
                    raise TrialNotStarted(message["message"])
                elif kind == "error" and message["code"] not in ("not_playing", "queue_full", "rate_limited"):
                    raise PilotFlowError(f"websocket error {message['code']}: {message['message']}")
                elif kind == "trial_end":
                    self.outcome.trials += 1
                    break
        finally:
            if pacer is not None:
                pacer.cancel()
