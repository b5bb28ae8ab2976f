"""Security checks: every admin route answers the same bare 401 without the admin token; a participant's
token reaches only their own session and trial (REST and websocket); joins are rate-limited per client
address; pages carry the security headers; and under load (several simulated participants at once, the
benchmark's own clients) no message carries anything outside the participant's field of view."""

from __future__ import annotations

import asyncio
import json
import re
import sys
from typing import Any

import httpx
import pytest
from steakhouse_masking import check_masked
from steakhouse_test_robots import simulated_partner
from steakhouse_testing import REPO, Player, eventually, wait_stored
from websockets.asyncio.client import connect

from server.security import JoinLimiter
from store.tables import EventRow, TrialRow

sys.path.insert(0, str(REPO / "benchmarks" / "load"))
from simulated_participant import run_load

pytestmark = pytest.mark.store_agnostic

UNAUTHORIZED = {"detail": {"code": "unauthorized", "message": "a valid token is required"}}
BAD_ADMIN = [{}, {"Authorization": "Bearer wrong"}, {"Authorization": "admin-secret"},
             {"Authorization": "Basic admin-secret"}, {"Authorization": "Bearer admin-secretx"},
             {"Authorization": "bearer"}, {"Authorization": "Bearer " + "a" * 5000}]


def admin_routes(app: Any) -> list[tuple[str, str]]:
    """Every (method, path) of the admin API (from its OpenAPI schema), path parameters filled in."""
    found = []
    for path, operations in app.openapi()["paths"].items():
        if path.startswith("/api/admin"):
            found += [(method.upper(), re.sub(r"\{[^}]+\}", "1", path)) for method in sorted(operations)]
    return found


def test_every_admin_route_answers_a_bare_401_without_the_admin_token(live_server, study_file):
    server = live_server([study_file()])
    routes = admin_routes(server.app)
    assert len(routes) >= 9, routes
    with httpx.Client(base_url=server.url, timeout=30) as client:
        participant = client.post("/api/studies/tiny/join", json={}).json()
        as_participant = {"Authorization": f"Bearer {participant['token']}"}
        for method, path in routes:
            for headers in [*BAD_ADMIN, as_participant]:
                for params in ({}, {"token": "admin-secret"}):
                    response = client.request(method, path, headers=headers, params=params,
                                              json={"test_run": True} if method == "POST" else None)
                    where = f"{method} {path} {headers} {params}"
                    assert response.status_code == 401, where
                    assert response.json() == UNAUTHORIZED, where
                    assert response.headers["www-authenticate"] == "Bearer", where
                    assert participant["participant_id"] not in response.text
    with server.services.store.transaction() as session:
        row = session.query(EventRow).count()
    assert row == 0, "refused admin calls must change nothing"


async def _ready(server: Any, pid: str) -> tuple[Player, dict[str, Any]]:
    player = Player(server.url)
    joined = await player.join(PROLIFIC_PID=pid)
    await player.post("/api/session/consent", {"accept": True})
    await player.post("/api/session/instructions_done")
    return player, joined


def test_a_participant_token_reaches_only_its_own_session_and_trial(live_server, study_file):
    server = live_server([study_file(world={"orders": 1, "horizon": 600, "kb_delay": 1})])

    async def scenario() -> dict[str, Any]:
        alice, joined_a = await _ready(server, "alice")
        bob, joined_b = await _ready(server, "bob")
        sock_a, sock_b = await alice.socket(), await bob.socket()
        hello_a, hello_b = await sock_a.recv(), await sock_b.recv()
        await sock_b.until(lambda m: m["type"] == "state")
        await sock_b.send("select_subtask", subtask="pickup_meat")
        await sock_b.until(lambda m: m["type"] == "ack")
        # Alice tries to steer Bob's trial from her own socket: extra fields are refused, nothing else names it.
        await sock_a.send_raw(json.dumps({"v": 1, "seq": 50, "type": "select_subtask", "subtask": "pickup_onion",
                                          "trial_id": hello_b["trial"]["id"]}))
        refused = await sock_a.until(lambda m: m["type"] == "error")
        await sock_a.send("interrupt", action="stop")
        await sock_a.until(lambda m: m["type"] == "ack")
        state_b = await sock_b.until(lambda m: m["type"] == "state")
        # REST: every participant route answers Alice's own data, whatever else the request names.
        views = []
        for params in ({}, {"participant_id": joined_b["participant_id"]}, {"token": bob.token}):
            response = await alice.http.get("/api/session", headers=alice.headers, params=params)
            views.append(response.json())
        completion = await alice.http.get("/api/session/completion", headers=alice.headers,
                                          params={"participant_id": joined_b["participant_id"]})
        forged = bob.token[:-2] + ("AA" if not bob.token.endswith("AA") else "BB")
        forged_rest = await alice.http.get("/api/session", headers={"Authorization": f"Bearer {forged}"})
        async with connect(server.url.replace("http", "ws") + f"/ws/play?token={forged}") as ws:
            forged_ws = json.loads(await asyncio.wait_for(ws.recv(), 10))
        # Joining with Bob's recruiting id from another browser does not get his session; his token still works.
        again = Player(server.url)
        rejoined = await again.http.post("/api/studies/tiny/join", json={"recruiting": {"PROLIFIC_PID": "bob"}})
        await again.close()
        stale = await bob.http.get("/api/session", headers=bob.headers)
        stale_ws = await sock_b.until(lambda m: m["type"] in ("state", "error"))
        for sock in (sock_a, sock_b):
            await sock.close()
        await alice.close()
        await bob.close()
        return {"hello_a": hello_a, "hello_b": hello_b, "refused": refused, "state_b": state_b, "views": views,
                "completion": completion, "forged_rest": forged_rest, "forged_ws": forged_ws, "joined_a": joined_a,
                "joined_b": joined_b, "rejoined": rejoined, "stale": stale, "stale_ws": stale_ws}

    r = asyncio.run(scenario())
    assert r["hello_a"]["trial"]["id"] != r["hello_b"]["trial"]["id"]
    assert r["refused"]["code"] == "invalid_message"
    assert r["state_b"]["subtask"] in ("pickup_meat", None), "Alice's stop must not reach Bob's trial"
    for v in r["views"]:
        assert v["participant_id"] == r["joined_a"]["participant_id"]
        assert r["joined_b"]["participant_id"] not in json.dumps(v)
    assert r["completion"].status_code == 409
    assert r["forged_rest"].status_code == 401 and r["forged_rest"].json() == UNAUTHORIZED
    assert r["forged_ws"]["code"] == "unauthorized"
    assert r["rejoined"].status_code == 409 and r["rejoined"].json()["detail"]["code"] == "already_started"
    assert "token" not in r["rejoined"].text and r["joined_b"]["participant_id"] not in r["rejoined"].text
    assert r["stale"].status_code == 200 and r["stale_ws"]["type"] == "state"

    def stored() -> tuple[dict[int, int], dict[int, int]]:
        with server.services.store.transaction() as session:
            events = session.query(EventRow).filter(EventRow.kind.in_(["select_subtask", "interrupt"])).all()
            trial_owner = {t.id: t.participant_id for t in session.query(TrialRow)}
            return {e.trial_id: e.participant_id for e in events}, trial_owner

    owners, trial_owner = eventually(stored, lambda found: len(found[0]) == 2)
    assert len(owners) == 2 and all(trial_owner[trial] == who for trial, who in owners.items())


def test_the_websocket_takes_the_token_as_a_subprotocol_so_it_stays_out_of_urls(live_server, study_file):
    server = live_server([study_file(world={"orders": 1, "horizon": 600, "kb_delay": 1})])
    url = server.url.replace("http", "ws") + "/ws/play"

    async def scenario() -> tuple[str | None, dict[str, Any], dict[str, Any], dict[str, Any]]:
        player, _ = await _ready(server, "subprotocol")
        async with connect(url, subprotocols=["steakhouse.v1", f"token.{player.token}"]) as ws:  # type: ignore[list-item]
            selected, hello = ws.subprotocol, json.loads(await asyncio.wait_for(ws.recv(), 10))
        async with connect(url, subprotocols=["steakhouse.v1", "token.not-a-token"]) as ws:  # type: ignore[list-item]
            forged = json.loads(await asyncio.wait_for(ws.recv(), 10))
        async with connect(url, subprotocols=["steakhouse.v1"]) as ws:  # type: ignore[list-item]
            missing = json.loads(await asyncio.wait_for(ws.recv(), 10))
        await player.close()
        return selected, hello, forged, missing

    selected, hello, forged, missing = asyncio.run(scenario())
    assert selected == "steakhouse.v1", "a browser drops the connection unless the server selects a subprotocol"
    assert hello["type"] == "hello" and hello["tick"] == 0
    assert forged["code"] == missing["code"] == "unauthorized"


def test_the_join_limiter_refills_per_address():
    now = [0.0]
    limiter = JoinLimiter(3, clock=lambda: now[0])
    assert [limiter.take("a") for _ in range(3)] == [0.0, 0.0, 0.0]
    assert limiter.take("a") == pytest.approx(20.0)
    assert limiter.take("b") == 0.0
    now[0] = 20.0
    assert limiter.take("a") == 0.0 and limiter.take("a") > 0
    assert all(JoinLimiter(0).take("a") == 0.0 for _ in range(1000))


def test_joins_are_rate_limited_per_client_address(live_server, study_file):
    server = live_server([study_file()], join_rate_per_minute=4)
    with httpx.Client(base_url=server.url, timeout=30) as client:
        first = [client.post("/api/studies/tiny/join", json={}) for _ in range(4)]
        limited = client.post("/api/studies/tiny/join", json={})
        unknown = client.post("/api/studies/nope/join", json={})
        # uvicorn takes the client address from X-Forwarded-For only from a trusted proxy (127.0.0.1 here).
        other = client.post("/api/studies/tiny/join", json={}, headers={"X-Forwarded-For": "203.0.113.9"})
        token = first[0].json()["token"]
        session = client.get("/api/session", headers={"Authorization": f"Bearer {token}"})
    assert [r.status_code for r in first] == [200] * 4
    assert limited.status_code == 429 and unknown.status_code == 429
    assert limited.json() == {"detail": {"code": "rate_limited",
                                         "message": "too many joins from this address; try again shortly"}}
    assert 1 <= int(limited.headers["retry-after"]) <= 15
    assert other.status_code == 200, "another address has its own budget"
    assert session.status_code == 200, "only joins are limited"


def test_pages_and_answers_carry_the_security_headers(live_server, study_file):
    server = live_server([study_file()], static_dir=REPO / "static")
    with httpx.Client(base_url=server.url, timeout=30) as client:
        answers = {path: client.get(path) for path in ("/", "/consent", "/js/main.js", "/css/client.css",
                                                      "/api/session", "/api/studies/tiny", "/healthz")}
        docs = client.get("/docs")
    for path, response in answers.items():
        assert response.status_code in (200, 401), path
        headers = response.headers
        assert headers["x-content-type-options"] == "nosniff", path
        assert headers["referrer-policy"] == "no-referrer", path
        assert headers["x-frame-options"] == "DENY", path
        csp = dict(part.strip().split(" ", 1) for part in headers["content-security-policy"].split(";"))
        assert csp["default-src"] == "'self'" and csp["script-src"] == "'self'", path
        assert csp["frame-ancestors"] == "'none'" and csp["object-src"] == "'none'", path
        assert csp["style-src"] == "'self'" and "unsafe" not in csp["script-src"] + csp["default-src"], path
        assert [k for k, v in csp.items() if "unsafe" in v] == ["style-src-attr"], path
    assert "<script" in answers["/"].text and 'type="module"' in answers["/"].text
    assert not re.search(r"<script(?![^>]*\bsrc=)[^>]*>", answers["/"].text), "no inline scripts in the page"
    assert " style=" not in answers["/"].text and "<style" not in answers["/"].text
    assert docs.headers["content-security-policy"] == "frame-ancestors 'none'"


# -- the masking property under load --------------------------------------------------------------------

def test_no_participant_message_leaves_the_field_of_view_under_load(live_server, study_file):
    study = study_file(kitchens=["mid_2", "none_3"], factors=["kitchen"],
                       world={"orders": 2, "horizon": 400, "kb_delay": 3, "fov_angle": 120})
    server = live_server([study], robot_factory=simulated_partner, join_rate_per_minute=0)
    stats = asyncio.run(run_load(server.url, "tiny", participants=6, seconds=6.0, seed=11, ramp_s=0.5,
                                 capture=True))
    # Every tick a message showed must be stored before it can be compared (the writer commits in batches).
    wait_stored(server.services.store, {t.trial_id: max((m["tick"] for m in t.messages if m["type"] == "state"),
                                                        default=0) for t in stats.transcripts})
    assert not stats.errors, stats.errors[:5]
    # How many ticks 6 s hold depends on the machine's load; what the property needs is that every participant
    # played, and (below) that the robot was both shown and hidden.
    assert len(stats.transcripts) >= 6
    assert all(any(m["type"] == "state" for m in t.messages) for t in stats.transcripts)
    shown = hidden = 0
    for transcript in stats.transcripts:
        s, h = check_masked(server, transcript.trial_id, transcript.messages)
        shown, hidden = shown + s, hidden + h
    assert shown > 0 and hidden > 0, "the load must show and hide the robot to test anything"
