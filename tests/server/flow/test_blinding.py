"""Blinding: nothing a participant's browser can reach names their condition, robot, kitchen, planner or
condition order (``docs/protocol.md`` §1). A probe plays a whole study — practice, every condition, the quiz,
every questionnaire — through REST and the websocket as a browser would, provokes the errors a participant
can meet, loads every file of the participant client, and searches every byte received."""

from __future__ import annotations

import asyncio
import contextlib
import json
from typing import Any

import httpx
import pytest
from steakhouse_blinding import Recorder, forbidden_names, hits
from steakhouse_test_robots import simulated_partner
from steakhouse_testing import REPO, http_client
from websockets.asyncio.client import connect
from websockets.exceptions import ConnectionClosedOK
from websockets.typing import Subprotocol

from study_config.study import load_study

pytestmark = pytest.mark.store_agnostic

STUDY = {
    "title": "FOV-aware robot versus the showing robot, baseline and no_rollout (none_3, mid_2)",
    "description": "fov_aware vs fov_aware_showing vs baseline vs no_rollout",
    "notes": "conditions: fov_aware@none_3 …",
    "kitchens": ["none_3", "mid_2"], "robots": ["fov_aware", "fov_aware_showing", "baseline", "no_rollout"],
    "factors": ["robot", "kitchen"],
    "practice": [{"kitchen": "side_1", "robot": "stay"}],
    "world": {"orders": 1, "horizon": 12, "kb_delay": 1, "fov_angle": 100},
    "quiz": {"questions": [{"id": "seen", "text": "What do you see?", "options": ["Everything", "Your view"],
                            "answer": 2, "explanation": "Only what is in front of you."}]},
}


def client_files() -> list[str]:
    """Every file of the participant client (the admin pages are behind the admin token's API and hold no
    study data; they are not part of what a participant is sent)."""
    static = REPO / "static"
    return sorted("/" + str(p.relative_to(static)) for p in static.rglob("*")
                  if p.is_file() and p.parts[len(static.parts)] not in ("admin", "vendor"))


def protocols(token: str) -> list[Subprotocol]:
    """The websocket subprotocols the client offers: the protocol version and the session token."""
    return [Subprotocol("steakhouse.v1"), Subprotocol(f"token.{token}")]


async def play_trial(base: str, token: str, record: Recorder) -> None:
    """Connect, provoke the errors a participant can meet, and play (first available subtask) to the end."""
    async with connect(base.replace("http", "ws", 1) + "/ws/play", subprotocols=protocols(token),
                       max_size=1 << 22) as ws:
        await ws.send("not json")
        await ws.send(json.dumps({"v": 1, "seq": 1, "type": "select_subtask", "subtask": "no_such_task"}))
        seq = 1
        while True:
            frame = await asyncio.wait_for(ws.recv(), 20)
            record.add("ws", frame)
            message = json.loads(frame)
            if message["type"] == "trial_end":
                return
            if message["type"] == "state" and message["subtask"] is None and message["available"]:
                seq += 1
                # The round may have ended as we chose (its trial_end and the close received, still unread): the
                # send then fails, and the next recv() returns that trial_end.
                with contextlib.suppress(ConnectionClosedOK):
                    await ws.send(json.dumps({"v": 1, "seq": seq, "type": "select_subtask",
                                              "subtask": message["available"][0]}))


async def probe(base: str, record: Recorder) -> dict[str, Any]:
    async with http_client(base) as http:
        async def call(method: str, path: str, token: str | None = None, **kwargs: Any) -> httpx.Response:
            headers = {"Authorization": f"Bearer {token}"} if token else {}
            response: httpx.Response = await http.request(method, path, headers=headers, **kwargs)
            record.add(f"{method} {path} → {response.status_code}", response.content)
            return response

        for path in ["/", "/?study=probe&PROLIFIC_PID=x", *client_files(), "/api/protocol", "/openapi.json"]:
            assert (await call("GET", path)).status_code == 200, path
        await call("GET", "/api/studies/probe")
        await call("GET", "/api/studies/nope")
        await call("POST", "/api/studies/probe/join", json={"recruiting": {"PROLIFIC_PID": 5}})
        joined = (await call("POST", "/api/studies/probe/join", json={"recruiting": {"PROLIFIC_PID": "probe-1"}}))
        token = joined.json()["token"]
        await call("POST", "/api/studies/probe/join", json={"recruiting": {"PROLIFIC_PID": "probe-1"}})
        await call("GET", "/api/session", "not-a-token")
        await call("POST", "/api/session/device", token, json={
            "screen_width": 1920, "screen_height": 1080, "viewport_width": 1600, "viewport_height": 900,
            "pixel_ratio": 1, "fine_pointer": True, "touch": False})
        await call("POST", "/api/session/instructions_done", token)
        states = []
        while (state := (await call("GET", "/api/session", token)).json()["state"]) not in ("done", "screened_out"):
            states.append(state)
            if state == "consent":
                await call("POST", "/api/session/consent", token, json={"accept": True})
            elif state == "instructions":
                await call("POST", "/api/session/instructions_done", token)
            elif state == "quiz":
                await call("POST", "/api/session/quiz", token, json={"answers": {"seen": 0}})
                await call("POST", "/api/session/quiz", token, json={"answers": {"seen": 1}})
            elif state == "questionnaire":
                await call("POST", "/api/session/questionnaire", token, json={"questionnaire_id": "q", "answers": {}})
                await call("POST", "/api/session/questionnaire", token,
                           json={"questionnaire_id": "q", "answers": {"a": 3}})
            else:
                await play_trial(base, token, record)
        await call("GET", "/api/session/completion", token)
        async with connect(base.replace("http", "ws", 1) + "/ws/play", subprotocols=protocols(token)) as ws:
            record.add("ws (after the end)", await asyncio.wait_for(ws.recv(), 10))
        return {"states": states}


def test_nothing_a_participant_receives_names_their_conditions(live_server, study_file, capsys):
    path = study_file("probe", **STUDY)
    study = load_study(path)
    server = live_server([path], robot_factory=simulated_partner, static_dir=REPO / "static")
    record = Recorder()
    result = asyncio.run(probe(server.url, record))
    assert result["states"].count("trial") == len(study.conditions) == 8
    assert result["states"].count("practice") == 1 and "quiz" in result["states"]
    hello = next(json.loads(data) for where, data in record.received
                 if where == "ws" and json.loads(data)["type"] == "hello")
    protocol_words = {*hello["subtasks"], *hello["interrupts"], *hello["needs"].values(), "practice", "main"}
    forbidden, exempt = forbidden_names(study, protocol_words)
    assert exempt == {"stay": "a robot"}, "only the practice robot shares its name with a key (the stay interrupt)"
    leak = Recorder([("what join answered before", b'{"condition_order": ["fov_aware@none_3", "baseline@mid_2"]}')])
    assert len(hits(leak, forbidden)) == 7, "the probe finds the condition order, its conditions, robots and kitchens"
    found = hits(record, forbidden)
    with capsys.disabled():
        print(f"\nblinding probe: {record.messages} messages, {record.bytes} bytes received, "
              f"{len(forbidden)} names searched, {len(found)} hits")
    assert found == [], "\n".join(found)
    kinds = {json.loads(data)["type"] for where, data in record.received if where == "ws"}
    assert {"hello", "state", "error", "trial_end"} <= kinds, "the probe met the websocket's errors too"
    statuses = {where.rsplit(" ", 1)[-1] for where, _ in record.received if "→" in where}
    assert {"200", "401", "404", "409", "422"} <= statuses, statuses


def test_every_session_view_and_hello_carry_the_studys_one_field_of_view(live_server, study_file):
    """The instructions draw the participant's cone from ``session.fov_angle`` and the trial page from
    ``hello.fov_angle``, so both are always sent. The angle is the study's ``world.fov_angle``, the same in
    every condition (a condition is a robot, a kitchen and a view), so it tells nothing about the condition."""
    path = study_file("probe", **STUDY)
    server = live_server([path], robot_factory=simulated_partner, static_dir=REPO / "static")
    record = Recorder()
    asyncio.run(probe(server.url, record))
    sessions = [json.loads(data) for where, data in record.received if where == "GET /api/session → 200"]
    hellos = [m for m in (json.loads(data) for where, data in record.received if where == "ws") if m["type"] == "hello"]
    assert {s["state"] for s in sessions} >= {"consent", "instructions", "quiz", "practice", "trial", "questionnaire"}
    assert len(hellos) == 9, "the practice round and the eight conditions"
    assert [s.get("fov_angle") for s in sessions] == [100] * len(sessions)
    assert [h.get("fov_angle") for h in hellos] == [100] * len(hellos)
