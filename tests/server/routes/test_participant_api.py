"""The participant REST API: join, the state machine over HTTP (409 for illegal moves), questionnaires
(422 with typed problems), completion codes; every call scoped by the participant's token."""

from __future__ import annotations

import asyncio
import json
from typing import Any

import httpx
import pytest
from websockets.asyncio.client import connect

RECRUITING = {"completion_code": "DONE42", "completion_redirect_url": "https://example.org/done?cc={code}",
              "screen_out_code": "OUT7", "screen_out_redirect_url": "https://example.org/out?cc={code}"}


@pytest.fixture
def server(live_server, study_file):
    # Rounds of 5 ticks that nobody plays: engagement is not what this file tests (test_play_participation.py).
    return live_server([study_file(world={"orders": 1, "horizon": 5, "kb_delay": 1}, recruiting=RECRUITING,
                                   validity={"min_participant_actions": 0, "max_idle_pct": 100})])


@pytest.fixture
def client(server):
    with httpx.Client(base_url=server.url, timeout=30) as client:
        yield client


def ws_messages(server, token: str, until: str | None = None) -> list[dict[str, Any]]:
    async def run() -> list[dict[str, Any]]:
        out = []
        async with connect(server.url.replace("http", "ws") + f"/ws/play?token={token}") as ws:
            while True:
                try:
                    out.append(json.loads(await asyncio.wait_for(ws.recv(), 10)))
                except Exception:
                    return out
                if out[-1]["type"] == until:
                    return out

    return asyncio.run(run())


def join(client, **recruiting) -> tuple[dict[str, Any], dict[str, str]]:
    response = client.post("/api/studies/tiny/join", json={"recruiting": recruiting})
    assert response.status_code == 200, response.text
    body = response.json()
    return body, {"Authorization": f"Bearer {body['token']}"}


def test_join_answers_a_token_but_never_the_condition_order(client):
    body, headers = join(client, PROLIFIC_PID="p1", STUDY_ID="s")
    assert set(body) == {"token", "participant_id", "study_id", "state", "rejoined"}
    assert body["state"] == "consent" and body["rejoined"] is False and len(body["token"]) > 30
    session = client.get("/api/session", headers=headers).json()
    assert session["state"] == "consent" and "Consent" in session["consent"]
    assert not {"condition_order", "order_index"} & set(session)
    assert client.get("/api/studies/tiny").json() == {"id": "tiny",
                                                      "url_parameters": ["PROLIFIC_PID", "STUDY_ID", "SESSION_ID"]}


def test_unknown_studies_and_bad_bodies_are_refused(client):
    assert client.post("/api/studies/nope/join", json={}).json() == {
        "detail": {"code": "unknown_study", "message": "no such study"}}
    assert client.post("/api/studies/tiny/join", json={"recruiting": {"PROLIFIC_PID": 5}}).status_code == 422
    assert client.post("/api/studies/tiny/join", json={"surprise": 1}).status_code == 422


@pytest.mark.parametrize("headers", [{}, {"Authorization": "Bearer nope"}, {"Authorization": "Basic abc"}])
def test_the_session_needs_a_valid_token(client, headers):
    response = client.get("/api/session", headers=headers)
    assert response.status_code == 401
    assert response.json() == {"detail": {"code": "unauthorized", "message": "a valid token is required"}}


def test_declining_consent_ends_with_the_screen_out_code(client):
    _, headers = join(client)
    assert client.get("/api/session/completion", headers=headers).status_code == 409
    session = client.post("/api/session/consent", json={"accept": False}, headers=headers).json()
    assert session["state"] == "screened_out"
    assert session["completion"] == {"kind": "screen_out", "code": "OUT7",
                                     "redirect_url": "https://example.org/out?cc=OUT7", "reason": "declined_consent"}
    again = client.post("/api/session/consent", json={"accept": True}, headers=headers)
    assert again.status_code == 409 and again.json()["detail"]["code"] == "illegal_transition"


def test_the_whole_flow_with_illegal_moves_refused(client, server):
    _, headers = join(client)
    assert client.post("/api/session/instructions_done", headers=headers).status_code == 409
    assert client.post("/api/session/consent", json={"accept": True}, headers=headers).json()["state"] == "instructions"
    session = client.post("/api/session/instructions_done", headers=headers).json()
    assert session["state"] == "trial" and session["trial"] == {
        "kind": "main", "index": 0, "number": 1, "total": 1, "kind_number": 1, "kind_total": 1,
        "scored": True, "status": "new", "view": "top_down", "websocket": "/ws/play", "kitchen_waits": False}
    refused = client.post("/api/session/questionnaire", json={"questionnaire_id": "q", "answers": {"a": 1}},
                          headers=headers)
    assert refused.status_code == 409 and refused.json()["detail"]["state"] == "trial"
    messages = ws_messages(server, headers["Authorization"][7:], until="trial_end")
    assert messages[-1]["reason"] == "horizon" and messages[-1]["next"] == "questionnaire"
    session = client.get("/api/session", headers=headers).json()
    assert session["state"] == "questionnaire" and [i["id"] for i in session["questionnaire"]["items"]] == ["a", "b"]
    problems = client.post("/api/session/questionnaire", json={"questionnaire_id": "q", "answers": {"b": 9}},
                           headers=headers)
    assert problems.status_code == 422
    assert [(p["loc"][-1], p["type"]) for p in problems.json()["detail"]] == [("a", "missing"), ("b", "out_of_range")]
    wrong = client.post("/api/session/questionnaire", json={"questionnaire_id": "x", "answers": {}}, headers=headers)
    assert wrong.status_code == 409
    done = client.post("/api/session/questionnaire", json={"questionnaire_id": "q", "answers": {"a": 3}},
                       headers=headers).json()
    assert done["state"] == "done" and done["trials_done"] == 1
    assert client.get("/api/session/completion", headers=headers).json() == {
        "kind": "completion", "code": "DONE42", "redirect_url": "https://example.org/done?cc=DONE42", "reason": None}
    services = server.services
    from store.tables import AnswerRow

    with services.store.transaction() as session_:
        answers = {(a.item_id, a.value, a.after_trial) for a in session_.query(AnswerRow)}
        assert answers == {("a", 3, 0), ("b", None, 0)}
        assert all(a.trial_id is not None for a in session_.query(AnswerRow))


def test_the_websocket_refuses_bad_tokens_and_participants_not_in_a_trial(client, server):
    assert ws_messages(server, "nope") == [{"v": 1, "seq": 1, "type": "error", "code": "unauthorized",
                                            "message": "a valid participant token is required", "ref": None}]
    body, _ = join(client)
    [message] = ws_messages(server, body["token"])
    assert message["code"] == "no_trial" and "consent" in message["message"]


def test_a_placeholder_code_never_reaches_a_real_participant_and_test_runs_see_a_stand_in(live_server, study_file):
    from steakhouse_testing import Player, play_every_trial, signed_test_code

    placeholders = {"completion_code": "REPLACE-WITH-YOUR-COMPLETION-CODE",
                    "completion_redirect_url": "https://example.org/done?cc={code}",
                    "screen_out_code": "REPLACE-WITH-YOUR-SCREEN-OUT-CODE"}
    server = live_server([study_file(world={"orders": 1, "horizon": 5, "kb_delay": 1}, recruiting=placeholders)])

    async def finish(test_run: bool) -> tuple[dict[str, Any], dict[str, Any]]:
        player = Player(server.url)
        body = {"test_link": signed_test_code()} if test_run else {}
        joined = await player.http.post("/api/studies/tiny/join", json=body)
        player.token = joined.json()["token"]
        (await player.post("/api/session/consent", {"accept": True})).raise_for_status()
        (await player.post("/api/session/instructions_done")).raise_for_status()
        await play_every_trial(player)
        view = await player.session()
        code = (await player.http.get("/api/session/completion", headers=player.headers)).json()
        await player.close()
        return view, code

    with httpx.Client(base_url=server.url, timeout=30) as client:
        _body, headers = join(client, PROLIFIC_PID="declines")
        declined = client.post("/api/session/consent", json={"accept": False}, headers=headers).json()
    assert declined["completion"] == {"kind": "screen_out", "code": None, "redirect_url": None,
                                      "reason": "declined_consent", "not_set_up": True}
    real_view, real_code = asyncio.run(finish(test_run=False))
    assert real_view["state"] == "done"
    for completion in (real_view["completion"], real_code):
        assert completion["code"] is None and completion["redirect_url"] is None and completion["not_set_up"]
    assert "REPLACE-WITH" not in json.dumps([declined, real_view, real_code])
    test_view, test_end = asyncio.run(finish(test_run=True))
    assert test_view["completion"]["code"] == test_end["code"] == "TEST-RUN"
    assert test_view["completion"]["redirect_url"] is None and test_view["completion"]["test_run"] is True
    assert "not_set_up" not in test_view["completion"]
