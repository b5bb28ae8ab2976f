"""Participants who game the engagement rules, and one who plays like a person, through the real server on the
paper's clock with the study's default validity rules; the rounds' wall clock is moved by the test, never slept.

- A held "." (stay) — on this clock the browser sends one press — and a random task every 8 s (clicked among the
  enabled buttons, as ``pilot.scripts`` does) are screened out, each told the rule their round failed, with the
  value measured in it.
- The human-like simulated participant (``pilot``) thinking 0.5–3 s per choice completes.
"""

from __future__ import annotations

import asyncio
import contextlib
from typing import Any

import httpx
import numpy as np
import pytest
from steakhouse_test_robots import simulated_partner
from steakhouse_testing import ENGAGEMENT_RULES, ManualClock, Player

from pilot.client import Seat, SimulatedParticipant
from pilot.config import ParticipantConfig
from pilot.scripts import Script
from study_config.catalog import load_one
from study_config.study.validity import Validity

pytestmark = pytest.mark.store_agnostic

PAPER_CLOCK = {"mode": "wait_for_participant", "tick_rate_hz": 5, "max_round_seconds": 240, "idle_nudge_seconds": 10}
CODES = {"completion_code": "DONE-1", "screen_out_code": "OUT-1"}
ADMIN = {"Authorization": "Bearer admin-secret"}


def paper_clock_study(study_file: Any, **extra: Any) -> Any:
    """One main round in none_3 on the paper's clock, the study's default engagement rules (robot health aside)."""
    return study_file(kitchens=["none_3"], robots=["stay"], timing=PAPER_CLOCK, world={"orders": 1, "horizon": 400},
                      recruiting=CODES, validity=ENGAGEMENT_RULES, **extra)


def main_trial(server: Any, public_id: str) -> dict[str, Any]:
    rows = httpx.get(f"{server.url}/api/admin/trials", params={"participant_id": public_id}, headers=ADMIN,
                     timeout=10).json()
    return next(t for t in rows if t["kind"] == "main")


def measured(trial: dict[str, Any], rule: str) -> float:
    """The value of ``rule`` in the stored trial, computed again from its activity columns."""
    if rule == "idle":
        return float(trial["idle_pct"])
    if rule == "task_steps":
        team = int(trial["task_steps"]) + int(trial["robot_task_steps"])
        return 100.0 * int(trial["task_steps"]) / team if team else 0.0
    if rule == "refused_tasks":
        return 100.0 * int(trial["refused_steps"]) / int(trial["selections"])
    return float(trial["selections"] + trial["interrupts"])


def assert_screened_out_for_a_true_reason(server: Any, public_id: str, session: dict[str, Any]) -> str:
    assert session["state"] == "screened_out"
    completion = session["completion"]
    assert (completion["kind"], completion["code"], completion["reason"]) == ("screen_out", "OUT-1", "low_engagement")
    detail = completion["detail"]
    trial = main_trial(server, public_id)
    assert trial["low_engagement"] and detail["round"] == 1
    assert abs(detail["value"] - measured(trial, detail["rule"])) < 0.1, "the value said is the value stored"
    return str(detail["rule"])


async def send(sock: Any, body: dict[str, Any]) -> int:
    """Send a script's message (``{"type": …, …}``) as the browser would; its ``seq``."""
    fields = dict(body)
    return int(await sock.send(fields.pop("type"), **fields))


async def flow_to_round(player: Player) -> dict[str, Any]:
    joined: dict[str, Any] = await player.join()
    await player.post("/api/session/consent", {"accept": True})
    await player.post("/api/session/instructions_done")
    return joined


def test_a_held_key_is_one_press_and_a_round_left_standing_is_screened_out_as_idle(live_server, study_file):
    clock = ManualClock()
    server = live_server([paper_clock_study(study_file)], clock=clock)

    async def scenario():
        player = Player(server.url)
        joined = await flow_to_round(player)
        sock = await player.socket()
        hello = await sock.recv()
        await sock.until(lambda m: m["type"] == "state")
        script = Script("hold_key")
        assert script.delay(hello["mode"], hello["tick_rate_hz"], 1) is None, "held: one press on this clock"
        await send(sock, script.send(None, hello["needs"], np.random.default_rng(0)))
        await sock.until(lambda m: m["type"] == "state" and m["tick"] == 1)
        while True:
            clock.advance(20.0)
            with contextlib.suppress(TimeoutError):
                end = await sock.until(lambda m: m["type"] == "trial_end", timeout=0.5)
                break
        await sock.close()
        session = await player.session()
        await player.close()
        return joined, end, session

    joined, end, session = asyncio.run(scenario())
    assert (end["reason"], end["ticks"], end["next"]) == ("time_limit", 1, "screened_out")
    assert assert_screened_out_for_a_true_reason(server, joined["participant_id"], session) == "idle"


def test_a_random_task_every_8_seconds_is_screened_out_with_its_rule(live_server, study_file):
    clock = ManualClock()
    server = live_server([paper_clock_study(study_file)], clock=clock)
    rng = np.random.default_rng(8)

    async def scenario():
        player = Player(server.url)
        joined = await flow_to_round(player)
        sock = await player.socket()
        hello = await sock.recv()
        state = await sock.until(lambda m: m["type"] == "state")
        script = Script("random_task", every_seconds=8.0)
        while True:
            seq = await send(sock, script.send(state["you"]["held"], hello["needs"], rng))
            # The page shows the task walk and work; the script clicks again 8 s after its last click.
            message = await sock.until(lambda m, sent=seq: m["type"] == "trial_end" or (
                m["type"] == "state" and m["ack"] >= sent and m["subtask"] is None), timeout=30)
            if message["type"] == "trial_end":
                break
            state = message
            clock.advance(script.every_seconds)
        await sock.close()
        session = await player.session()
        await player.close()
        return joined, session

    joined, session = asyncio.run(scenario())
    rule = assert_screened_out_for_a_true_reason(server, joined["participant_id"], session)
    assert rule in ("idle", "refused_tasks")


def test_the_human_like_simulated_participant_takes_part(live_server, study_file):
    clock = ManualClock()
    path = study_file(kitchens=["none_3"], robots=["baseline"], timing=PAPER_CLOCK,
                      world={"orders": 2, "horizon": 400, "kb_delay": 3}, recruiting=CODES, validity=ENGAGEMENT_RULES)
    server = live_server([path], robot_factory=simulated_partner, clock=clock)

    async def think(seconds: float) -> None:
        """The participant's wall-clock waits pass on the round's clock (a little real time lets the world step)."""
        clock.advance(seconds)
        await asyncio.sleep(min(seconds, 0.2))

    seat = Seat(server.url, "admin-secret", load_one(path), ParticipantConfig(), pace="realtime", sleep=think)
    outcome = asyncio.run(SimulatedParticipant(seat, "pilot-human-1", (1, 0)).run())
    assert outcome.completed and outcome.selections > 0
    trial = main_trial(server, outcome.participant_id)
    assert not trial["low_engagement"], trial["engagement_reason"]
    assert trial["task_steps"] > 0 and trial["stand_ticks"] == 0
    assert Validity().min_task_step_pct > 0, "the rules judged it"
