"""Text no store can keep (a lone UTF-16 surrogate, NUL) gets a 422 naming the field on every route that takes
text, on SQLite and PostgreSQL alike, and nothing is stored; the error body itself is valid UTF-8."""

from __future__ import annotations

import asyncio
import json
from typing import Any

import httpx
from steakhouse_testing import Player, play_to_end

from server.text_input import first_problem, safe, text_problem
from store.tables import AnswerRow, ParticipantRow, QuizAttemptRow

UNSTORABLE = ["\ud800", "a\udfffb", "\x00", "x\x00"]
QUESTIONNAIRE = {"id": "q", "items": [{"id": "a", "text": "A", "scale": {"min": 1, "max": 5}},
                                      {"id": "note", "type": "text", "text": "Anything?", "required": False}]}
QUIZ = {"questions": [{"id": "seen", "text": "?", "options": ["a", "b"], "answer": 1, "explanation": "a"}]}


def test_the_checker_finds_the_first_unstorable_string_at_any_depth():
    assert text_problem("ordinary ü 😀") is None
    surrogate, nul = text_problem("\udc80"), text_problem("\x00")
    assert surrogate is not None and "surrogate" in surrogate and nul is not None and "NUL" in nul
    assert first_problem({"a": [1, "ok", {"b": "\ud800"}]}) == (("body", "a", 2, "b"), text_problem("\ud800"))
    problem = first_problem({"ok": 1, "\x00key": 2})
    assert problem is not None
    loc, reason = problem
    assert loc == ("body", "\\x00key") and reason.startswith("a field name")
    assert first_problem({"a": ["fine", None, 1.5, True]}) is None
    assert safe("a\ud800\x00").encode("utf-8") == b"a\\ud800\\x00"


def _post(client: httpx.Client, path: str, body: dict[str, Any], token: str | None = None) -> httpx.Response:
    headers = {"Content-Type": "application/json"}
    if token:
        headers["Authorization"] = f"Bearer {token}"
    return client.post(path, content=json.dumps(body).encode(), headers=headers)


def _at_questionnaire(url: str) -> str:
    async def run() -> str:
        player = Player(url)
        await player.ready(PROLIFIC_PID="played")
        (await player.post("/api/session/quiz", {"answers": {"seen": 0}})).raise_for_status()
        sock = await player.socket()
        await play_to_end(sock)
        await sock.close()
        await player.close()
        token: str = player.token
        return token

    return asyncio.run(run())


def test_every_route_with_text_answers_422_naming_the_field_and_stores_nothing(live_server, study_file):
    study = study_file(world={"orders": 1, "horizon": 20, "kb_delay": 1}, questionnaires=[QUESTIONNAIRE], quiz=QUIZ)
    server = live_server([study])
    played = _at_questionnaire(server.url)
    with httpx.Client(base_url=server.url, timeout=30) as client:
        fresh = client.post("/api/studies/tiny/join", json={}).json()["token"]
        _post(client, "/api/session/consent", {"accept": True}, fresh)
        _post(client, "/api/session/instructions_done", {}, fresh)
        public_id = client.get("/api/session", headers={"Authorization": f"Bearer {played}"}).json()["participant_id"]
        cases: list[tuple[str, dict[str, Any], str | None, list[str]]] = []
        for bad in UNSTORABLE:
            cases += [
                ("/api/studies/tiny/join", {"recruiting": {"PROLIFIC_PID": bad}}, None, ["recruiting", "PROLIFIC_PID"]),
                ("/api/studies/tiny/join", {"recruiting": {"STUDY_ID": "s", bad: "x"}}, None,
                 ["recruiting", safe(bad)]),
                ("/api/studies/tiny/resume", {"code": bad}, None, ["code"]),
                ("/api/session/quiz", {"answers": {"seen": bad}}, fresh, ["answers", "seen"]),
                ("/api/session/quiz", {"answers": {bad: 1}}, fresh, ["answers", safe(bad)]),
                ("/api/session/questionnaire", {"questionnaire_id": "q", "answers": {"a": 3, "note": bad}}, played,
                 ["answers", "note"]),
                ("/api/session/questionnaire", {"questionnaire_id": bad, "answers": {"a": 3}}, played,
                 ["questionnaire_id"]),
                (f"/api/admin/participants/{public_id}/flags", {"excluded": True, "reason": f"bot {bad}"},
                 "admin-secret", ["reason"]),
            ]
        for path, body, token, field in cases:
            response = _post(client, path, body, token)
            assert response.status_code == 422, (path, body, response.status_code, response.text[:300])
            problem = response.json()["detail"][0]
            assert problem["loc"] == ["body", *field] and problem["type"] == "string_unstorable", (path, problem)
            response.content.decode("utf-8")
    with server.services.store.transaction() as session:
        assert session.query(ParticipantRow).count() == 2, "no refused join made a participant"
        assert session.query(QuizAttemptRow).filter(QuizAttemptRow.participant_id != None).count() == 1  # noqa: E711
        assert session.query(AnswerRow).count() == 0
        excluded = session.query(ParticipantRow).filter_by(public_id=public_id).one()
        assert not excluded.excluded
