"""Test runs come from the admin only (``server/admin/test_links.py``): a participant's ``test_run`` is ignored,
a test run needs a test link the admin signed (for that study, not expired, unaltered), and a test run never sees
the study's real completion code, nor its redirect."""

from __future__ import annotations

import json
import time
from typing import Any

import httpx
from steakhouse_testing import signed_test_code

from server.admin.test_links import make_test_code, signing_key
from store.tables import ParticipantRow

ADMIN = {"Authorization": "Bearer admin-secret"}
CODES = {"completion_code": "REAL-CODE-77", "completion_redirect_url": "https://recruit.example/done?cc={code}",
         "screen_out_code": "REAL-OUT-77", "require_id": True}


def finish(client: httpx.Client, token: str) -> list[Any]:
    """Decline consent (the shortest way to an end page): every answer the participant's browser got on the way."""
    headers = {"Authorization": f"Bearer {token}"}
    seen = [client.post("/api/session/consent", json={"accept": False}, headers=headers).json(),
            client.get("/api/session", headers=headers).json(),
            client.get("/api/session/completion", headers=headers).json()]
    return seen


def test_a_participant_cannot_make_themselves_a_test_run(live_server, study_file):
    server = live_server([study_file(recruiting=CODES)])
    with httpx.Client(base_url=server.url, timeout=30) as client:
        refused = client.post("/api/studies/tiny/join", json={"test_run": True})
        assert refused.status_code == 422 and refused.json()["detail"]["code"] == "recruit_id_required"
        joined = client.post("/api/studies/tiny/join", json={"test_run": True,
                                                             "recruiting": {"PROLIFIC_PID": "sneaky"}})
        assert joined.status_code == 200
        seen = finish(client, joined.json()["token"])
    with server.services.store.transaction() as session:
        row = session.query(ParticipantRow).one()
        assert row.test_run is False, "the participant's test_run was ignored"
    assert seen[-1]["code"] == "REAL-OUT-77" and "test_run" not in seen[-1], "a real participant's end page"


def test_a_test_run_needs_an_admin_signed_link_and_never_sees_the_real_code(live_server, study_file):
    server = live_server([study_file(recruiting=CODES), study_file("other")])
    secret = signing_key("admin-secret")
    with httpx.Client(base_url=server.url, timeout=30) as client:
        links = client.get("/api/admin/studies/tiny/links", headers=ADMIN).json()
        code = links["test_run"]["path"].split("#test=", 1)[1]
        bad = [code[:-2] + ("AA" if not code.endswith("AA") else "BB"),  # altered
               make_test_code(secret, "tiny", int(time.time()) - 1),  # expired
               signed_test_code("other"),  # another study's
               make_test_code(signing_key("another-token"), "tiny", int(time.time()) + 600),  # not this admin's
               "nonsense"]
        for value in bad:
            refused = client.post("/api/studies/tiny/join", json={"test_link": value})
            assert refused.status_code == 410 and refused.json()["detail"]["code"] == "test_link_invalid", value
        joined = client.post("/api/studies/tiny/join", json={"test_link": code})
        assert joined.status_code == 200, "no recruiting id needed for a test run"
        seen = finish(client, joined.json()["token"])
        again = client.post("/api/studies/tiny/join", json={"test_link": code})
        assert again.status_code == 200, "a test link works for several test runs until it expires"
        # A participant the admin marked as a test run is a test run too.
        real = client.post("/api/studies/tiny/join", json={"recruiting": {"PROLIFIC_PID": "marked"}}).json()
        client.post(f"/api/admin/participants/{real['participant_id']}/flags", headers=ADMIN,
                    json={"test_run": True}).raise_for_status()
        seen += finish(client, real["token"])
    with server.services.store.transaction() as session:
        assert sorted(r.test_run for r in session.query(ParticipantRow)) == [True, True, True]
    assert "REAL-" not in json.dumps(seen) and "recruit.example" not in json.dumps(seen)
    ends = [s for s in seen if "kind" in s] + [s["completion"] for s in seen if s.get("completion")]
    assert ends and all(e["code"] == "TEST-RUN" and e["redirect_url"] is None for e in ends), ends
