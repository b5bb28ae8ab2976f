"""A recruiting id is not a password: joining with another participant's id from a browser without their
token gets nothing of their session (``409 already_started``, the attempt stored), their token and live trial
go on untouched; their own browser comes back with the same token; and the experimenter moves a participant
to a new device with a one-time, expiring resume link."""

from __future__ import annotations

import asyncio
import time
from typing import Any

import httpx
from steakhouse_testing import Player, eventually, http_client, signed_test_code

from server.admin.resume import link_secret, make_code, read_code
from server.flow.service import ALREADY_STARTED
from store import participants
from store.tables import EventRow, ParticipantRow

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
        async with http_client(server.url) as attacker:
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


def test_using_a_resume_link_closes_the_old_browsers_game_socket_at_once(live_server, study_file):
    server = live_server([study_file(world={"orders": 1, "horizon": 3000, "kb_delay": 1})])

    async def scenario() -> tuple[list[dict[str, Any]], int | None, dict[str, Any], dict[str, Any]]:
        old = Player(server.url)
        await old.ready(PROLIFIC_PID="switcher")
        joined = await old.session()
        sock = await old.socket()
        # The round is under way (a tick played), so the new browser's game is a resumed one.
        await sock.until(lambda m: m["type"] == "state" and m["tick"] >= 1)
        made = (await old.http.post(f"/api/admin/participants/{joined['participant_id']}/resume_link",
                                    headers=ADMIN)).json()
        code = made["path"].split("#resume=", 1)[1]
        new = Player(server.url)
        new.token = (await new.http.post("/api/studies/tiny/resume", json={"code": code})).json()["token"]
        ended: list[dict[str, Any]] = []
        try:
            while True:  # no reconnect attempt, no heartbeat: the server itself closes the old socket
                ended.append(await sock.recv(timeout=5))
        except Exception:
            pass
        again = await new.socket()
        hello = await again.recv()
        first = await again.until(lambda m: m["type"] == "hello" or m["type"] == "state")
        await again.close()
        for player in (old, new):
            await player.close()
        return ended, sock.ws.close_code, hello, first

    ended, code, hello, first = asyncio.run(scenario())
    assert ended[-1]["type"] == "error" and ended[-1]["code"] == "moved", ended[-3:]
    assert code == 4401
    assert hello["type"] == "hello" and hello["resumed"] is True and first["type"] == "state"


PHONE = {"screen_width": 390, "screen_height": 844, "viewport_width": 390, "viewport_height": 700,
         "pixel_ratio": 3, "fine_pointer": False, "touch": True}
LAPTOP = {"screen_width": 1440, "screen_height": 900, "viewport_width": 1280, "viewport_height": 720,
          "pixel_ratio": 2, "fine_pointer": True, "touch": False}


def test_recruiting_ids_are_compared_normalised(live_server, study_file):
    server = live_server([study_file()])
    with httpx.Client(base_url=server.url, timeout=30) as client:
        first = client.post("/api/studies/tiny/join", json={"recruiting": {"PROLIFIC_PID": "AbC123"}}).json()
        client.post("/api/session/consent", json={"accept": False},
                    headers={"Authorization": f"Bearer {first['token']}"})
        for typed in ("abc123", "ABC123 ", "  aBc123", "ABC123\t"):
            again = client.post("/api/studies/tiny/join", json={"recruiting": {"PROLIFIC_PID": typed}})
            assert again.status_code == 409 and again.json()["detail"]["code"] == "already_started", typed
        other = client.post("/api/studies/tiny/join", json={"recruiting": {"PROLIFIC_PID": "abc1234"}})
        assert other.status_code == 200
    with server.services.store.transaction() as session:
        row = participants.by_public_id(session, first["participant_id"])
        assert row is not None and row.recruit_id == "AbC123" and row.recruit_key == "abcl23"
        assert row.recruiting["PROLIFIC_PID"] == "AbC123"


PROLIFIC_ID = "5f3a9c1e2b7d4a6f8e0c1b2a"
LOOK_ALIKES = {
    "zero-width space": PROLIFIC_ID[:6] + "\u200b" + PROLIFIC_ID[6:],
    "zero-width joiner": PROLIFIC_ID[:6] + "\u200d" + PROLIFIC_ID[6:],
    "soft hyphen": PROLIFIC_ID[:6] + "\u00ad" + PROLIFIC_ID[6:],
    "full-width letters": "".join(chr(ord(c) + 0xFEE0) for c in PROLIFIC_ID),
    "combining accent": PROLIFIC_ID[:3] + "\u0301" + PROLIFIC_ID[3:],
    "Cyrillic look-alike": PROLIFIC_ID.replace("a", "\u0430").replace("e", "\u0435").replace("c", "\u0441"),
    "O for 0, l for 1": PROLIFIC_ID.replace("0", "O").replace("1", "l"),
}


def test_look_alike_ids_are_the_same_participant(live_server, study_file):
    server = live_server([study_file()])
    with httpx.Client(base_url=server.url, timeout=30) as client:
        first = client.post("/api/studies/tiny/join", json={"recruiting": {"PROLIFIC_PID": PROLIFIC_ID}}).json()
        mine = {"Authorization": f"Bearer {first['token']}"}
        itself = client.post("/api/studies/tiny/join", json={"recruiting": {"PROLIFIC_PID": PROLIFIC_ID}})
        assert itself.status_code == 409
        for name, look_alike in LOOK_ALIKES.items():
            assert look_alike != PROLIFIC_ID
            other = client.post("/api/studies/tiny/join", json={"recruiting": {"PROLIFIC_PID": look_alike}})
            assert (other.status_code, other.json()) == (409, itself.json()), name
            own = client.post("/api/studies/tiny/join", headers=mine,
                              json={"recruiting": {"PROLIFIC_PID": look_alike}})
            assert own.status_code == 200 and own.json()["participant_id"] == first["participant_id"], name
    with server.services.store.transaction() as session:
        rows = session.query(ParticipantRow).all()
        assert [(r.recruit_id, r.public_id) for r in rows] == [(PROLIFIC_ID, first["participant_id"])]


def test_a_study_that_requires_the_id_refuses_a_join_without_it(live_server, study_file):
    server = live_server([study_file(recruiting={"require_id": True})])
    with httpx.Client(base_url=server.url, timeout=30) as client:
        for recruiting in ({}, {"PROLIFIC_PID": "   "}, {"STUDY_ID": "s"}):
            refused = client.post("/api/studies/tiny/join", json={"recruiting": recruiting})
            assert refused.status_code == 422, refused.text
            assert refused.json()["detail"]["code"] == "recruit_id_required" and "PROLIFIC_PID" in refused.text
        ignored = client.post("/api/studies/tiny/join", json={"test_run": True})
        assert ignored.status_code == 422, "a participant's own test_run is ignored: the id is still required"
        assert client.post("/api/studies/tiny/join", json={"test_link": signed_test_code()}).status_code == 200
        assert client.post("/api/studies/tiny/join", json={"recruiting": {"PROLIFIC_PID": "p"}}).status_code == 200
    with server.services.store.transaction() as session:
        assert session.query(ParticipantRow).count() == 2


def test_a_session_whose_device_was_refused_continues_on_a_laptop_only_with_the_phones_code(live_server, study_file):
    server = live_server([study_file()])
    with httpx.Client(base_url=server.url, timeout=30) as client:
        phone = client.post("/api/studies/tiny/join", json={"recruiting": {"PROLIFIC_PID": "walker"}}).json()
        on_phone = {"Authorization": f"Bearer {phone['token']}"}
        view = client.post("/api/session/device", json=PHONE, headers=on_phone).json()
        assert view["device"]["ok"] is False and view["state"] == "consent"
        code = view["handoff"]["code"]
        assert client.get("/api/session", headers=on_phone).json()["handoff"]["code"] == code
        walker = {"recruiting": {"PROLIFIC_PID": "walker"}}
        alone = client.post("/api/studies/tiny/join", json=walker)
        assert alone.status_code == 409 and alone.json()["detail"]["code"] == "handoff_code_required"
        wrong = client.post("/api/studies/tiny/join", json={**walker, "handoff": "AAAAA-BBBBB"})
        assert wrong.status_code == 409 and wrong.json()["detail"]["code"] == "handoff_code_wrong"
        assert client.get("/api/session", headers=on_phone).status_code == 200, "the phone's session is untouched"
        laptop = client.post("/api/studies/tiny/join", json={**walker, "handoff": f" {code.lower()} "})
        assert laptop.status_code == 200, laptop.text
        body = laptop.json()
        assert body["participant_id"] == phone["participant_id"] and body["token"] != phone["token"]
        assert body["rejoined"] is True
        on_laptop = {"Authorization": f"Bearer {body['token']}"}
        assert client.get("/api/session", headers=on_phone).status_code == 401, "the phone's token stops working"
        assert client.post("/api/studies/tiny/join", json={**walker, "handoff": code}).status_code == 409, "once"
        passed = client.post("/api/session/device", json=LAPTOP, headers=on_laptop).json()
        assert passed["device"]["ok"] is True and "handoff" not in passed
        assert client.post("/api/session/consent", json={"accept": True}, headers=on_laptop).status_code == 200
        # Once the device passed, the session is the laptop's: a third browser is refused as before.
        third = client.post("/api/studies/tiny/join", json=walker)
        assert third.status_code == 409 and third.json()["detail"]["code"] == "already_started"
    _, kinds = stored(server, phone["participant_id"])
    assert kinds.count("session_claimed") == 1 and kinds.count("handoff_refused") == 2  # wrong, then reused


def test_wrong_hand_off_codes_lock_the_hand_off(live_server, study_file):
    from server.flow.handoff import MAX_WRONG

    server = live_server([study_file()])
    with httpx.Client(base_url=server.url, timeout=30) as client:
        phone = client.post("/api/studies/tiny/join", json={"recruiting": {"PROLIFIC_PID": "guessed"}}).json()
        on_phone = {"Authorization": f"Bearer {phone['token']}"}
        code = client.post("/api/session/device", json=PHONE, headers=on_phone).json()["handoff"]["code"]
        guesses = [client.post("/api/studies/tiny/join", json={"recruiting": {"PROLIFIC_PID": "guessed"},
                                                               "handoff": f"GUESS-{n:05d}"}).json()["detail"]["code"]
                   for n in range(MAX_WRONG + 3)]
        right = client.post("/api/studies/tiny/join", json={"recruiting": {"PROLIFIC_PID": "guessed"},
                                                             "handoff": code})
    assert guesses == ["handoff_code_wrong"] * MAX_WRONG + ["handoff_locked"] * 3
    assert right.status_code == 409 and right.json()["detail"]["code"] == "handoff_locked"
    _, kinds = stored(server, phone["participant_id"])
    assert kinds.count("handoff_refused") == MAX_WRONG, "the attempts beyond the lock store nothing"


def test_a_session_past_its_first_step_is_not_claimed_even_if_its_device_is_refused_later(live_server, study_file):
    server = live_server([study_file()])
    with httpx.Client(base_url=server.url, timeout=30) as client:
        first = client.post("/api/studies/tiny/join", json={"recruiting": {"PROLIFIC_PID": "steady"}}).json()
        headers = {"Authorization": f"Bearer {first['token']}"}
        client.post("/api/session/device", json=LAPTOP, headers=headers)
        client.post("/api/session/consent", json={"accept": True}, headers=headers)
        client.post("/api/session/device", json=PHONE, headers=headers)  # the window was made small
        other = client.post("/api/studies/tiny/join", json={"recruiting": {"PROLIFIC_PID": "steady"}})
        assert other.status_code == 409
        assert client.get("/api/session", headers=headers).status_code == 200
