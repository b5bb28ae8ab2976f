"""Participants who game the engagement rules, and one who plays like a person, through the real server on the
paper's clock with the study's default validity rules; the rounds' wall clock is moved by the test, never slept.

- A held "." (stay) — on this clock the browser sends one press — and a random task every 8 s (clicked among the
  enabled buttons, as ``pilot.scripts`` does) are screened out, each told the rule their round failed, with the
  value measured in it.
- The human-like simulated participant (``pilot``) thinking 0.5–3 s per choice completes.
- A round whose robot broke (its decisions late, so the round is robot-invalid) is not judged: a participant who
  left it standing goes on.
"""

from __future__ import annotations

import asyncio
import contextlib
from collections import Counter
from typing import Any

import httpx
import numpy as np
import pytest
from steakhouse_test_robots import simulated_partner, slow
from steakhouse_testing import ENGAGEMENT_RULES, ManualClock, Player

from pilot.client import Seat, SimulatedParticipant
from pilot.config import ParticipantConfig
from pilot.scripts import STAY, Script
from study_config.catalog import load_one
from study_config.study.validity import DEFAULT_MAX_MISSED_DECISIONS_PCT, Validity

pytestmark = pytest.mark.store_agnostic

PAPER_CLOCK = {"mode": "wait_for_participant", "tick_rate_hz": 5, "max_round_seconds": 240, "idle_nudge_seconds": 10}
WITH_ROBOT_HEALTH = {**ENGAGEMENT_RULES, "max_missed_decisions_pct": DEFAULT_MAX_MISSED_DECISIONS_PCT}
"""The study's default engagement and robot-health rules together."""
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


def refusals(server: Any, trial_id: int) -> Counter[tuple[str, str]]:
    """The trial's refused tasks, counted by (reason, task)."""
    events = httpx.get(f"{server.url}/api/admin/trials/{trial_id}/events", headers=ADMIN, timeout=10).json()
    return Counter((e["payload"]["reason"], e["payload"]["subtask"]) for e in events if e["kind"] == "subtask_blocked")


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


async def left_standing(sock: Any, clock: ManualClock) -> dict[str, Any]:
    """The participant does nothing more: the round's wall clock is moved on until it ends; its ``trial_end``."""
    while True:
        clock.advance(20.0)
        with contextlib.suppress(TimeoutError):
            end: dict[str, Any] = await sock.until(lambda m: m["type"] == "trial_end", timeout=0.5)
            return end


async def closed(player: Player, sock: Any) -> dict[str, Any]:
    """Close the round's socket; the participant's session as it stands after the round."""
    await sock.close()
    session: dict[str, Any] = await player.session()
    await player.close()
    return session


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
        end = await left_standing(sock, clock)
        session = await closed(player, sock)
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
        return joined, await closed(player, sock)

    joined, session = asyncio.run(scenario())
    rule = assert_screened_out_for_a_true_reason(server, joined["participant_id"], session)
    assert rule in ("idle", "refused_tasks")


def test_the_human_like_simulated_participant_takes_part(live_server, study_file):
    """With the study's robot health too: on a machine too busy for the robot's decision deadline the robot stands
    where it is, in the participant's way, and the round is robot-invalid rather than theirs to answer for."""
    clock = ManualClock()
    path = study_file(kitchens=["none_3"], robots=["baseline"], timing=PAPER_CLOCK,
                      world={"orders": 2, "horizon": 400, "kb_delay": 3}, recruiting=CODES, validity=WITH_ROBOT_HEALTH)
    server = live_server([path], robot_factory=simulated_partner, clock=clock)

    async def think(seconds: float) -> None:
        """The participant's wall-clock waits pass on the round's clock (a little real time lets the world step)."""
        clock.advance(seconds)
        await asyncio.sleep(min(seconds, 0.2))

    seat = Seat(server.url, "admin-secret", load_one(path), ParticipantConfig(), pace="realtime", sleep=think)
    outcome = asyncio.run(SimulatedParticipant(seat, "pilot-human-1", (1, 0)).run())
    trial = main_trial(server, outcome.participant_id)
    # What a failure needs to be understood: the refusals, the robot's lateness, the presses and choices.
    story = (trial["engagement_reason"], refusals(server, trial["trial_id"]), trial["missed_decisions_pct"],
             outcome.interrupts, outcome.selections)
    assert outcome.completed and outcome.selections > 0, story
    assert not trial["low_engagement"], story
    assert trial["task_steps"] > 0 and trial["stand_ticks"] == 0
    assert Validity().min_task_step_pct > 0, "the rules judged it"


def test_a_round_the_robot_broke_is_not_judged_and_never_screens_out(live_server, study_file):
    """The ``slow`` robot (0.3 s a decision, past every deadline of a 5 Hz round after the first) makes the round
    robot-invalid as it is played; the participant pressed "." and then left it standing, which a working robot's
    round screens out as idle (above), and goes on."""
    clock = ManualClock()
    path = study_file(kitchens=["none_3"], robots=["stay"], timing=PAPER_CLOCK, world={"orders": 1, "horizon": 400},
                      recruiting=CODES, validity=WITH_ROBOT_HEALTH)
    server = live_server([path], robot_factory=slow, clock=clock)
    presses = 30  # more late decisions than 5 % of the horizon: invalid as it happens

    async def scenario():
        player = Player(server.url)
        joined = await flow_to_round(player)
        sock = await player.socket()
        await sock.recv()
        await sock.until(lambda m: m["type"] == "state")
        for tick in range(1, presses + 1):
            await send(sock, STAY)
            await sock.until(lambda m, t=tick: m["type"] == "state" and m["tick"] == t)
        end = await left_standing(sock, clock)
        session = await closed(player, sock)
        return joined, end, session

    joined, end, session = asyncio.run(scenario())
    assert (end["reason"], end["ticks"]) == ("time_limit", presses) and end["next"] != "screened_out"
    assert session["state"] != "screened_out"
    trial = main_trial(server, joined["participant_id"])
    assert trial["invalid"] and trial["missed_decisions_pct"] > DEFAULT_MAX_MISSED_DECISIONS_PCT
    assert trial["idle_pct"] > Validity().max_idle_pct, "left standing: idle past the rule"
    assert not trial["low_engagement"] and trial["engagement_reason"] is None
