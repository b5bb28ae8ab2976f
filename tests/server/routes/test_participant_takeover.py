"""A recruiting id is not a password: joining with another participant's id from a browser without their
token gets nothing of their session (``409 already_started``, the attempt stored), their token and live trial
go on untouched; their own browser comes back with the same token; and the experimenter moves a participant
to a new device with a one-time, expiring resume link."""

from __future__ import annotations

import asyncio
import time
from typing import Any

import httpx
from steakhouse_testing import Player, eventually

from server.admin.resume import link_secret, make_code, read_code
from server.flow.service import ALREADY_STARTED
from server.store import participants
from server.store.tables import EventRow

ADMIN = {"Authorization": "Bearer admin-secret"}


def stored(server: Any, public_id: str) -> tuple[str, list[str]]:
    """The participant's token hash and the kinds of their events without a trial."""
    with server.services.store.transaction() as session:
        row = participants.by_public_id(session, public_id)
        assert row is not None
        kinds = [e.kind for e in session.query(EventRow).filter(EventRow.participant_id == row.id,
                                                                 EventRow.trial_id.is_(None))]
        return row.token_hash, kinds


def test_a_takeover_leaves_the_victims_session_and_token_untouched(live_server, study_file):
    server = live_server([study_file(world={"orders": 1, "horizon": 3000, "kb_delay": 1})])

    async def scenario() -> dict[str, Any]:
        victim = Player(server.url)
        joined = await victim.join(PROLIFIC_PID="victim")
        await victim.post("/api/session/consent", {"accept": True})
        await victim.post("/api/session/instructions_done")
        sock = await victim.socket()
        await sock.until(lambda m: m["type"] == "state")
        before = await victim.session()
        hash_before = stored(server, joined["participant_id"])[0]
        other = Player(server.url)
        await other.join(PROLIFIC_PID="someone-else")
        attempts = []
        async with httpx.AsyncClient(base_url=server.url, timeout=30) as attacker:
            for headers in ({}, {"Authorization": "Bearer forged"}, other.headers):
                attempts.append(await attacker.post("/api/studies/tiny/join", headers=headers,
                                                    json={"recruiting": {"PROLIFIC_PID": "victim"}}))
        after_ws = await sock.until(lambda m: m["type"] in ("state", "error"))
        tick = after_ws.get("tick", 0)
        later = await sock.until(lambda m: m["type"] in ("state", "error") and m.get("tick", 0) > tick)
        after = await victim.session()
        back = await victim.http.post("/api/studies/tiny/join", headers=victim.headers,
                                      json={"recruiting": {"PROLIFIC_PID": "victim", "SESSION_ID": "again"}})
        await sock.close()
        for player in (victim, other):
            await player.close()
        return {"joined": joined, "token": victim.token, "attempts": attempts, "before": before, "after": after,
                "ws": [after_ws, later], "back": back, "hash_before": hash_before}

    r = asyncio.run(scenario())
    for attempt in r["attempts"]:
        assert attempt.status_code == 409
        assert attempt.json() == {"detail": {"code": "already_started", "message": ALREADY_STARTED}}
        assert r["joined"]["participant_id"] not in attempt.text
    assert [m["type"] for m in r["ws"]] == ["state", "state"], "the victim's trial goes on in their browser"
    assert r["after"]["state"] == r["before"]["state"] == "trial" and r["after"]["step"] == r["before"]["step"]
    hash_after, kinds = stored(server, r["joined"]["participant_id"])
    assert hash_after == r["hash_before"], "the victim's token is unchanged"
    assert kinds.count("join_refused") == 3, "every attempt is stored"
    back = r["back"].json()
    assert r["back"].status_code == 200 and back["token"] == r["token"] and back["rejoined"] is True
    assert back["participant_id"] == r["joined"]["participant_id"]


def test_a_resume_link_moves_a_participant_to_a_new_device_once(live_server, study_file):
    server = live_server([study_file()], resume_link_minutes=5)
    with httpx.Client(base_url=server.url, timeout=30) as client:
        joined = client.post("/api/studies/tiny/join", json={"recruiting": {"PROLIFIC_PID": "mover"}}).json()
        old = {"Authorization": f"Bearer {joined['token']}"}
        assert client.post("/api/session/consent", json={"accept": True}, headers=old).status_code == 200
        assert client.post("/api/admin/participants/nobody/resume_link", headers=ADMIN).status_code == 404
        assert client.post(f"/api/admin/participants/{joined['participant_id']}/resume_link").status_code == 401
        made = client.post(f"/api/admin/participants/{joined['participant_id']}/resume_link", headers=ADMIN).json()
        assert made["path"].startswith("/?study=tiny#resume=") and made["url"].endswith(made["path"])
        code = made["path"].split("#resume=", 1)[1]
        parsed = read_code(code)
        assert parsed is not None and 240 < parsed.expires - time.time() <= 300

        def redeem(value: str) -> httpx.Response:
            return client.post("/api/studies/tiny/resume", json={"code": value})

        altered = redeem(code[:-2] + ("AA" if not code.endswith("AA") else "BB"))
        assert altered.status_code == 410 and altered.json()["detail"]["code"] == "link_invalid"
        assert redeem("nonsense").status_code == 410
        assert client.post("/api/studies/nope/resume", json={"code": code}).status_code == 404
        moved = redeem(code)
        assert moved.status_code == 200, moved.text
        body = moved.json()
        assert body["participant_id"] == joined["participant_id"] and body["token"] != joined["token"]
        new = {"Authorization": f"Bearer {body['token']}"}
        assert client.get("/api/session", headers=new).json()["state"] == "instructions", "progress kept"
        assert client.get("/api/session", headers=old).status_code == 401, "the old device is signed out"
        assert redeem(code).status_code == 410, "a link works once"
        with server.services.store.transaction() as session:
            row = participants.by_public_id(session, joined["participant_id"])
            assert row is not None
            expired = make_code(link_secret("admin-secret"), row.public_id, row.token_hash, int(time.time()) - 1)
        assert redeem(expired).status_code == 410, "an expired link is refused"
    _, kinds = eventually(lambda: stored(server, joined["participant_id"]),
                          lambda found: "resume_link_used" in found[1])
    assert kinds.count("resume_link_made") == 1 and kinds.count("resume_link_used") == 1
