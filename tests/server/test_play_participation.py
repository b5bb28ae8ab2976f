"""No completion without taking part: participants who stay idle or leave their rounds, through the
REST flow and the websocket in each clock, get the screen-out outcome with a reason, are listed with it, and stop
counting for assignment; one who plays is unaffected. The wait-for-participant clock's wall-clock limit is driven
by a clock the test moves by hand, never by sleeping."""

from __future__ import annotations

import asyncio
from typing import Any

import httpx
import pytest
from steakhouse_testing import ENGAGEMENT_RULES, ManualClock, Player, condition_order, play_to_end, until_unloaded

from store.tables import TrialRow

CLOCKS = ["fixed_rate", "wait_for_participant"]
ADMIN = {"Authorization": "Bearer admin-secret"}
CODES = {"completion_code": "DONE-1", "screen_out_code": "OUT-1"}


def two_round_study(study_file, mode: str, **extra):
    """Two main rounds (two kitchens, the ``stay`` robot): two condition orders, and a short horizon so that an
    idle round ends quickly on the fixed clock."""
    return study_file(kitchens=["practice", "none_3"], factors=["kitchen"],
                      timing={"mode": mode, "tick_rate_hz": 30, "idle_nudge_seconds": 1},
                      world={"orders": 1, "horizon": 45},
                      recruiting=CODES, **extra)


def admin_participant(server, public_id: str) -> dict[str, Any]:
    rows: list[dict[str, Any]] = httpx.get(f"{server.url}/api/admin/participants", headers=ADMIN, timeout=10).json()
    return next(p for p in rows if p["participant_id"] == public_id)


def admin_trials(server, public_id: str) -> list[dict[str, Any]]:
    rows: list[dict[str, Any]] = httpx.get(f"{server.url}/api/admin/trials", params={"participant_id": public_id},
                                           headers=ADMIN, timeout=10).json()
    return rows


async def next_joiner_order(server) -> list[str]:
    other = Player(server.url)
    joined = await other.join()
    await other.close()
    order: list[str] = condition_order(server.services, joined["participant_id"])
    return order


async def idle_round(sock, clock: ManualClock, mode: str, limit: float) -> tuple[list[dict[str, Any]], dict[str, Any]]:
    """Connect and never act; on the waiting clock, move the wall clock past the nudge and then the limit."""
    hello = await sock.recv()
    assert hello["type"] == "hello"
    await sock.until(lambda m: m["type"] == "state")
    if mode == "wait_for_participant":
        clock.advance(1.0)
        nudge = await sock.until(lambda m: m["type"] == "nudge")
        assert nudge["text"] == "Choose your next task"
        clock.advance(limit - 1.0)
    end = await sock.until(lambda m: m["type"] == "trial_end")
    return sock.received, end


@pytest.mark.parametrize("mode", CLOCKS)
def test_an_idle_participant_is_screened_out_listed_with_the_reason_and_not_counted(live_server, study_file, mode):
    clock = ManualClock()
    server = live_server([two_round_study(study_file, mode)], clock=clock)
    limit = 45 / 30 * 3

    async def scenario():
        player = Player(server.url)
        joined = await player.join()
        await player.post("/api/session/consent", {"accept": True})
        await player.post("/api/session/instructions_done")
        sock = await player.socket()
        received, end = await idle_round(sock, clock, mode, limit)
        await sock.close()
        session = await player.session()
        completion = await player.http.get("/api/session/completion", headers=player.headers)
        await player.close()
        return joined, received, end, session, completion.json(), await next_joiner_order(server)

    joined, received, end, session, completion, next_order = asyncio.run(scenario())
    public_id = joined["participant_id"]
    # The round ended on its own: at the horizon on the fixed clock, at the wall-clock limit on the waiting one.
    assert end["status"] == "finished"
    assert end["reason"] == ("horizon" if mode == "fixed_rate" else "time_limit")
    assert end["next"] == "screened_out"
    assert not any(m["type"] == "error" for m in received)
    # No completion code: the screen-out outcome, with a plain reason.
    assert session["state"] == "screened_out"
    assert completion == {"kind": "screen_out", "code": "OUT-1", "redirect_url": None, "reason": "low_engagement"}
    # The admin sees why: the trial is low-engagement with its reason, the participant screened out and uncounted.
    trial = next(t for t in admin_trials(server, public_id) if t["kind"] == "main")
    assert trial["low_engagement"] is True and "0 participant action(s)" in trial["engagement_reason"]
    assert (trial["selections"], trial["interrupts"], trial["idle_pct"]) == (0, 0, 100.0)
    row = admin_participant(server, public_id)
    assert row["status"] == "screened_out" and row["screen_out_reason"] == "low_engagement"
    assert row["low_engagement_trials"] == 1
    assert row["uncounted_reason"].startswith("main round 1 low_engagement")
    # The next participant gets the idle participant's order.
    assert next_order == condition_order(server.services, public_id)


async def open_the_first_round_and_leave(server):
    """A participant who opens their first main round and leaves it past the grace window: (join answer, the
    session afterwards, the order the next joiner gets)."""
    player = Player(server.url)
    joined = await player.join()
    await player.post("/api/session/consent", {"accept": True})
    await player.post("/api/session/instructions_done")
    sock = await player.socket()
    await sock.until(lambda m: m["type"] == "state")
    await sock.close()
    await until_unloaded(server.services, timeout=5)
    session = await player.session()
    await player.close()
    return joined, session, await next_joiner_order(server)


@pytest.mark.parametrize("mode", CLOCKS)
def test_an_abandoning_participant_is_screened_out_skips_the_questionnaire_and_is_not_counted(
        live_server, study_file, mode):
    server = live_server([two_round_study(study_file, mode, reconnect={"grace_seconds": 0.2,
                                                                        "after_grace": "abandon"})])

    joined, session, next_order = asyncio.run(open_the_first_round_and_leave(server))
    public_id = joined["participant_id"]
    assert session["state"] == "screened_out"
    assert session["completion"] == {"kind": "screen_out", "code": "OUT-1", "redirect_url": None,
                                     "reason": "abandoned_rounds"}
    trial = next(t for t in admin_trials(server, public_id) if t["kind"] == "main")
    assert (trial["status"], trial["end_reason"]) == ("abandoned", "grace_expired")
    row = admin_participant(server, public_id)
    assert row["screen_out_reason"] == "abandoned_rounds"
    assert row["uncounted_reason"].startswith("main round 1 abandoned")
    assert next_order == condition_order(server.services, public_id)


def test_a_participant_allowed_one_invalid_round_goes_on_without_its_questionnaire_and_stops_counting(
        live_server, study_file):
    server = live_server([two_round_study(study_file, "fixed_rate", validity={"max_invalid_rounds": 1},
                                          reconnect={"grace_seconds": 0.2, "after_grace": "abandon"})])

    joined, session, next_order = asyncio.run(open_the_first_round_and_leave(server))
    # The questionnaire about the unplayed round is skipped: the next step is the second round.
    assert session["state"] == "trial" and session["trial"]["index"] == 1
    row = admin_participant(server, joined["participant_id"])
    assert row["status"] == "in_progress" and row["uncounted_reason"].startswith("main round 1 abandoned")
    assert next_order == condition_order(server.services, joined["participant_id"])


@pytest.mark.parametrize("mode", CLOCKS)
def test_a_participant_who_plays_is_unaffected(live_server, study_file, mode):
    clock = ManualClock()
    path = study_file(kitchens=["practice", "none_3"], factors=["kitchen"],
                      timing={"mode": mode, "tick_rate_hz": 30}, recruiting=CODES, validity=ENGAGEMENT_RULES)
    server = live_server([path], clock=clock)

    async def scenario():
        player = Player(server.url)
        joined = await player.join()
        await player.post("/api/session/consent", {"accept": True})
        await player.post("/api/session/instructions_done")
        ends = []
        while (session := await player.session())["state"] in ("trial", "questionnaire"):
            if session["state"] == "questionnaire":
                (await player.post("/api/session/questionnaire",
                                   {"questionnaire_id": "q", "answers": {"a": 3}})).raise_for_status()
                continue
            sock = await player.socket()
            ends.append(await play_to_end(sock))
            await sock.close()
        await player.close()
        return joined, ends, session, await next_joiner_order(server)

    joined, ends, session, next_order = asyncio.run(scenario())
    public_id = joined["participant_id"]
    assert [e["reason"] for e in ends] == ["delivered", "delivered"]
    assert session["state"] == "done"
    assert session["completion"] == {"kind": "completion", "code": "DONE-1", "redirect_url": None, "reason": None}
    rows = [t for t in admin_trials(server, public_id) if t["kind"] == "main"]
    assert all(not t["low_engagement"] and t["engagement_reason"] is None for t in rows)
    # Who delivered: the robot stays put, so the one dish of each round is the participant's.
    assert all((t["delivered_by_participant"], t["delivered_by_robot"]) == (1, 0) for t in rows)
    assert all(t["selections"] >= 1 for t in rows)
    row = admin_participant(server, public_id)
    assert row["uncounted_reason"] is None and row["screen_out_reason"] is None
    # A completed participant counts: the next one gets the other order.
    assert next_order != condition_order(server.services, public_id)
    with server.services.store.transaction() as s:
        stored = [s.get(TrialRow, t["trial_id"]) for t in rows]
        assert all(r.idle_pct is not None and r.idle_pct < 90 for r in stored)


def test_a_participant_whose_device_was_refused_does_not_count_until_a_device_passes(live_server, study_file):
    server = live_server([two_round_study(study_file, "fixed_rate")])
    phone = {"screen_width": 390, "screen_height": 844, "viewport_width": 390, "viewport_height": 844,
             "pixel_ratio": 3, "fine_pointer": False, "touch": True}
    laptop = {**phone, "screen_width": 1440, "screen_height": 900, "viewport_width": 1440, "viewport_height": 800,
              "pixel_ratio": 1, "fine_pointer": True, "touch": False}

    async def scenario():
        player = Player(server.url)
        joined = await player.join()
        view = (await player.post("/api/session/device", phone)).json()
        refused_next = await next_joiner_order(server)
        row = admin_participant(server, joined["participant_id"])
        (await player.post("/api/session/device", laptop)).raise_for_status()
        passed = admin_participant(server, joined["participant_id"])
        await player.close()
        return joined, view, refused_next, row, passed

    joined, view, refused_next, row, passed = asyncio.run(scenario())
    assert view["device"]["ok"] is False
    assert row["uncounted_reason"] == "device_refused: small_screen; touch_only"
    assert refused_next == condition_order(server.services, joined["participant_id"])
    assert passed["uncounted_reason"] is None
