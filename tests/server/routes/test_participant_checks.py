"""The participant API's checks for online studies: the device reported on landing, the comprehension quiz
(retries with explanations, attempts stored, screen-out after too many), rating / choice / free-text
answers, durations filled into the texts, and what the pages are told about a round in progress or ended."""

from __future__ import annotations

import asyncio
from datetime import timedelta

import httpx
import pytest
from sqlalchemy import select, update
from steakhouse_testing import Player, eventually, http_client, play_to_end

from server.flow.answers import check_answers, stored_answer
from store.tables import AnswerRow, EventRow, ParticipantRow, QuizAttemptRow, TrialRow
from store.types import utcnow
from study_config.study.questionnaire import Questionnaire

QUIZ = {"max_attempts": 2, "questions": [
    {"id": "black", "text": "Black?", "options": ["Wall", "Out of view"], "answer": 2, "explanation": "Out of view."},
    {"id": "stop", "text": "Stop?", "options": ["Esc", "Enter", "Tab"], "answer": 1, "explanation": "Esc stops."}]}
ITEMS = [
    {"id": "fluency", "text": "Fluent.", "scale": {"min": 1, "max": 7}},
    {"id": "effort", "text": "Effort.", "scale": {"min": 1, "max": 7}, "reverse": True},
    {"id": "hand", "type": "choice", "text": "Hand?", "options": ["Left", "Right"]},
    {"id": "comment", "type": "text", "text": "Anything?", "required": False, "min_length": 2, "max_length": 40}]
RECRUITING = {"completion_code": "DONE", "screen_out_code": "OUT"}
DESKTOP = {"screen_width": 1920, "screen_height": 1080, "viewport_width": 1280, "viewport_height": 720,
           "pixel_ratio": 1, "fine_pointer": True, "touch": False}


@pytest.fixture
def client(live_server, study_file):
    server = live_server([study_file(
        quiz=QUIZ, recruiting=RECRUITING, world={"orders": 1, "horizon": 5, "kb_delay": 1},
        consent="Up to {minutes} minutes, rounds of at most {round_time}.",
        questionnaires=[{"id": "q", "items": ITEMS,
                         "scales": [{"id": "team", "items": ["fluency", "effort"]}]}])])
    with httpx.Client(base_url=server.url, timeout=30) as http:
        http.server = server  # type: ignore[attr-defined]
        yield http


def join(client, pid: str) -> dict[str, str]:
    body = client.post("/api/studies/tiny/join", json={"recruiting": {"PROLIFIC_PID": pid}}).json()
    return {"Authorization": f"Bearer {body['token']}"}


def stored(client, model, pid: str):
    with client.server.services.store.transaction() as session:
        participant = session.scalar(select(ParticipantRow).where(ParticipantRow.recruit_id == pid))
        rows = session.scalars(select(model).where(model.participant_id == participant.id)).all()
        return participant, rows


def test_the_device_is_recorded_and_a_phone_is_told_to_use_a_computer(client):
    headers = join(client, "dev-1")
    assert client.get("/api/session", headers=headers).json()["device"] is None
    phone = {**DESKTOP, "screen_width": 390, "screen_height": 844, "fine_pointer": False, "touch": True}
    view = client.post("/api/session/device", json=phone, headers=headers).json()
    assert view["device"] == {"ok": False, "problems": ["small_screen", "touch_only"], "min_width": 1024,
                              "min_height": 600}
    assert view["state"] == "consent", "nothing else changes: the same link works later on a computer"
    view = client.post("/api/session/device", json=DESKTOP, headers=headers).json()
    assert view["device"]["ok"] is True
    participant, events = stored(client, EventRow, "dev-1")
    assert participant.device == {**DESKTOP, "pixel_ratio": 1.0, "problems": [],
                                  "checked_at": participant.device["checked_at"]}
    assert [e.payload["problems"] for e in events if e.kind == "device_check"] == [["small_screen", "touch_only"], []]
    bad = client.post("/api/session/device", json={**DESKTOP, "screen_width": -1}, headers=headers)
    assert bad.status_code == 422 and bad.json()["detail"][0]["loc"] == ["body", "screen_width"]


def test_the_consent_states_the_studys_own_length(client):
    headers = join(client, "len-1")
    consent = client.get("/api/session", headers=headers).json()["consent"]
    assert consent.startswith("Up to ") and "rounds of at most 1 second." in consent and "{" not in consent


def to_quiz(client, pid: str) -> dict[str, str]:
    headers = join(client, pid)
    client.post("/api/session/consent", json={"accept": True}, headers=headers)
    view = client.post("/api/session/instructions_done", headers=headers).json()
    assert view["state"] == "quiz" and view["quiz"] == {
        "questions": [{"id": "black", "text": "Black?", "options": ["Wall", "Out of view"]},
                      {"id": "stop", "text": "Stop?", "options": ["Esc", "Enter", "Tab"]}],
        "attempts_used": 0, "max_attempts": 2}
    return headers


def test_a_wrong_quiz_answer_shows_its_explanation_and_a_retry_passes(client):
    headers = to_quiz(client, "quiz-1")
    incomplete = client.post("/api/session/quiz", json={"answers": {"black": 1}}, headers=headers)
    assert incomplete.status_code == 422
    assert [(p["loc"][-1], p["type"]) for p in incomplete.json()["detail"]] == [("stop", "missing")]
    first = client.post("/api/session/quiz", json={"answers": {"black": 0, "stop": 0}}, headers=headers).json()
    assert first["state"] == "quiz" and first["quiz"]["attempts_used"] == 1
    assert first["quiz_result"] == {"passed": False, "attempt": 1, "attempts_left": 1,
                                    "wrong": [{"id": "black", "explanation": "Out of view."}]}
    second = client.post("/api/session/quiz", json={"answers": {"black": 1, "stop": 0}}, headers=headers).json()
    assert second["quiz_result"]["passed"] is True and second["state"] == "trial"
    assert second["trial"]["status"] == "new"
    _, attempts = stored(client, QuizAttemptRow, "quiz-1")
    assert [(a.attempt, a.answers, a.wrong, a.passed) for a in attempts] == [
        (1, {"black": 0, "stop": 0}, ["black"], False), (2, {"black": 1, "stop": 0}, [], True)]


def test_too_many_failed_quiz_attempts_screen_out_with_the_screen_out_code(client):
    headers = to_quiz(client, "quiz-2")
    for _ in range(2):
        view = client.post("/api/session/quiz", json={"answers": {"black": 0, "stop": 2}}, headers=headers).json()
    assert view["state"] == "screened_out" and view["quiz_result"]["attempts_left"] == 0
    assert view["completion"] == {"kind": "screen_out", "code": "OUT", "redirect_url": None, "reason": "failed_quiz"}
    again = client.post("/api/session/quiz", json={"answers": {"black": 1, "stop": 0}}, headers=headers)
    assert again.status_code == 409
    participant, attempts = stored(client, QuizAttemptRow, "quiz-2")
    assert participant.status == "screened_out" and len(attempts) == 2


def test_rating_choice_and_text_answers_are_checked_and_stored_with_their_text(client):
    headers = to_quiz(client, "items-1")
    client.post("/api/session/quiz", json={"answers": {"black": 1, "stop": 0}}, headers=headers)
    async def play():
        player = Player(client.server.url)
        player.token = headers["Authorization"][7:]
        sock = await player.socket()
        await play_to_end(sock)
        await sock.close()
        await player.close()

    asyncio.run(play())
    view = client.get("/api/session", headers=headers).json()
    assert [(i["id"], i["type"]) for i in view["questionnaire"]["items"]] == [
        ("fluency", "rating"), ("effort", "rating"), ("hand", "choice"), ("comment", "text")]
    assert view["questionnaire"]["items"][2]["options"] == ["Left", "Right"]
    assert view["questionnaire"]["items"][3] == {**view["questionnaire"]["items"][3], "min_length": 2, "max_length": 40}
    bad = client.post("/api/session/questionnaire", headers=headers, json={"questionnaire_id": "q", "answers": {
        "fluency": 3, "effort": 8, "hand": 2, "comment": "x" * 41}})
    assert [(p["loc"][-1], p["type"]) for p in bad.json()["detail"]] == [
        ("effort", "out_of_range"), ("hand", "out_of_range"), ("comment", "too_long")]
    bad = client.post("/api/session/questionnaire", headers=headers, json={"questionnaire_id": "q", "answers": {
        "fluency": 3, "effort": 2, "hand": "Left", "comment": 5}})
    assert [(p["loc"][-1], p["type"]) for p in bad.json()["detail"]] == [
        ("hand", "not_integer"), ("comment", "not_text")]
    comment = ' =SUM(A1:A9), "quoted"\nsecond line '
    done = client.post("/api/session/questionnaire", headers=headers, json={"questionnaire_id": "q", "answers": {
        "fluency": 6, "effort": 2, "hand": 1, "comment": comment}}).json()
    assert done["state"] == "done"
    _, answers = stored(client, AnswerRow, "items-1")
    assert {a.item_id: (a.value, a.text) for a in answers} == {
        "fluency": (6, None), "effort": (2, None), "hand": (1, "Right"), "comment": (None, comment.strip())}


def test_an_optional_text_left_blank_is_no_answer():
    questionnaire = Questionnaire.model_validate({"id": "q", "items": ITEMS})
    comment = questionnaire.items[3]
    assert stored_answer(comment, "   ") == (None, None)
    assert check_answers(questionnaire, {"fluency": 1, "effort": 1, "hand": 0, "comment": "  "}) == []
    assert [p["type"] for p in check_answers(questionnaire, {"fluency": 1, "effort": 1, "hand": 0,
                                                             "comment": " a "})] == ["too_short"]


def test_a_round_in_progress_and_a_round_that_ended_while_away_are_told_apart(live_server, study_file):
    # Two rounds, one of which may be lost (validity.max_invalid_rounds), so the participant goes on to the next.
    server = live_server([study_file(reconnect={"grace_seconds": 0.3, "after_grace": "abandon"},
                                     world={"orders": 1, "horizon": 100000, "kb_delay": 1},
                                     kitchens=["practice", "none_3"], factors=["kitchen"],
                                     validity={"max_invalid_rounds": 1})])

    async def scenario():
        player = Player(server.url)
        await player.ready()
        before = (await player.session())["trial"]["status"]
        sock = await player.socket()
        hello = await sock.recv()
        await sock.until(lambda m: m["type"] == "state")
        # The stored last activity of a connected round is refreshed only by the periodic sweep: make it older than
        # the grace window, as a busy machine or a long sweep interval does. The round is still in progress.
        with server.services.store.transaction() as session:
            session.execute(update(TrialRow).where(TrialRow.id == int(hello["trial"]["id"]))
                            .values(last_active_at=utcnow() - timedelta(seconds=10)))
        during = (await player.session())["trial"]["status"]
        await sock.close()
        after = await player.session()
        for _ in range(200):  # the grace timer ends the round on the server: wait for that state, not a time
            if after["notice"] is not None:
                break
            await asyncio.sleep(0.05)
            after = await player.session()
        await player.close()
        return before, during, after

    before, during, after = asyncio.run(scenario())
    assert (before, during) == ("new", "in_progress")
    # The questionnaire about the unplayed round is skipped: the next round, with the notice why.
    assert after["state"] == "trial" and after["trial"]["index"] == 1 and after["notice"] == "round_ended_away"


def test_a_round_never_opens_on_a_device_the_check_refused(live_server, study_file):
    server = live_server([study_file(world={"orders": 1, "horizon": 5, "kb_delay": 1})])
    phone = {**DESKTOP, "screen_width": 390, "screen_height": 844, "fine_pointer": False, "touch": True}

    async def scenario():
        player = Player(server.url)
        await player.join(PROLIFIC_PID="skipper")
        (await player.post("/api/session/device", phone)).raise_for_status()
        await player.post("/api/session/consent", {"accept": True})
        await player.post("/api/session/instructions_done")  # a script can skip the page; the server cannot be
        sock = await player.socket()
        refused = await sock.recv()
        with pytest.raises(Exception):  # noqa: B017 - the server closes the socket
            await sock.recv(timeout=5)
        code = sock.ws.close_code
        (await player.post("/api/session/device", DESKTOP)).raise_for_status()
        again = await player.socket()
        hello = await again.recv()
        end = await play_to_end(again)
        await again.close()
        await player.close()
        return refused, code, hello, end

    refused, code, hello, end = asyncio.run(scenario())
    assert refused["type"] == "error" and refused["code"] == "device_refused" and code == 4403
    assert hello["type"] == "hello" and end["status"] == "finished"


def test_a_round_played_through_another_server_process_reads_as_in_progress(live_server, study_file):
    # Two server processes on one store (docs/deploy.md): the participant plays through the first, and their page
    # is loaded through the second, which does not run the round and judges it by its stored last activity. On the
    # paper's clock nothing is stored while the participant thinks (no tick), and the grace window (4 s) is far
    # shorter than the sweep (30 s): the first process refreshes that activity at least twice per window, so the
    # round never reads as ended while the participant is connected.
    study = study_file(reconnect={"grace_seconds": 4, "after_grace": "abandon"},
                       timing={"mode": "wait_for_participant", "tick_rate_hz": 30},
                       world={"orders": 1, "horizon": 100000, "kb_delay": 1})
    playing, other = live_server([study], sweep_interval_s=30), live_server([study], sweep_interval_s=30)
    assert playing.services.registry.touch_interval() == 2.0

    def stored_activity(trial_id: int):
        with playing.services.store.transaction() as session:
            return session.get(TrialRow, trial_id).last_active_at

    async def scenario():
        player = Player(playing.url)
        await player.ready()
        sock = await player.socket()
        hello = await sock.recv()
        await sock.until(lambda m: m["type"] == "state")
        trial_id = int(hello["trial"]["id"])
        first = await asyncio.to_thread(stored_activity, trial_id)
        # The participant thinks, and the world waits: wait (on the store) until the activity has been refreshed
        # past the grace window's length.
        refreshed = await asyncio.to_thread(
            eventually, lambda: stored_activity(trial_id), lambda t: t - first > timedelta(seconds=4.5), 20)
        async with http_client(other.url) as through_other:
            view = (await through_other.get("/api/session", headers=player.headers)).json()
        await sock.close()
        await player.close()
        return first, refreshed, view

    first, refreshed, view = asyncio.run(scenario())
    assert refreshed - first > timedelta(seconds=4.5), "the connected round's activity is refreshed within the grace"
    assert view["trial"]["status"] == "in_progress"
