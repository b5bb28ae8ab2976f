"""The admin API the dashboard uses beyond the basics: recruiting links, a participant's answers, the live
view's scene, replay frames (each tick's whole world with the participant's field of view, recomputed
with ``planner.fov``), all behind the admin token."""

from __future__ import annotations

import asyncio
from datetime import UTC, datetime, timedelta

import httpx
import pytest
from steakhouse_testing import Player, http_client, play_to_end

from planner.fov import view
from planner.geometry import Direction
from study_config import load_layout

ADMIN = {"Authorization": "Bearer admin-secret"}
RECRUITING = {"completion_code": "DONE-7", "completion_redirect_url": "https://recruit.example/done?cc={code}",
              "url_parameters": ["PROLIFIC_PID", "STUDY_ID", "SESSION_ID"]}


@pytest.fixture
def server(live_server, study_file):
    return live_server([study_file(recruiting=RECRUITING, world={"orders": 1, "horizon": 300, "kb_delay": 1,
                                                                 "fov_angle": 100})])


def fov_of(layout, frame, angle):
    human = frame["human"]
    cells = view(layout, (human["x"], human["y"]), Direction(human["facing"]), angle).cells
    return sorted([list(c) for c in cells], key=lambda c: (c[1], c[0]))


def test_the_new_endpoints_answer_401_without_the_token(server):
    with httpx.Client(base_url=server.url) as client:
        joined = client.post("/api/studies/tiny/join", json={}).json()
        for path in ("/api/admin/studies/tiny/links", f"/api/admin/participants/{joined['participant_id']}/answers",
                     "/api/admin/trials/1/frames"):
            for headers in ({}, {"Authorization": "Bearer nope"}, {"Authorization": f"Bearer {joined['token']}"}):
                response = client.get(path, headers=headers)
                assert response.status_code == 401, path
                assert response.json()["detail"]["code"] == "unauthorized"


def test_recruiting_links_carry_the_prolific_placeholders_and_the_code(server):
    with httpx.Client(base_url=server.url, headers=ADMIN) as client:
        links = client.get("/api/admin/studies/tiny/links").json()
        missing = client.get("/api/admin/studies/nope/links")
    assert links["participant"]["path"] == (
        "/?study=tiny&PROLIFIC_PID={{%PROLIFIC_PID%}}&STUDY_ID={{%STUDY_ID%}}&SESSION_ID={{%SESSION_ID%}}")
    assert links["participant"]["url"] == server.url + links["participant"]["path"]
    code = links["test_run"]["path"].removeprefix("/?study=tiny#test=")
    assert code != links["test_run"]["path"] and links["fresh_test_run"]["path"] == f"/?study=tiny&new=1#test={code}"
    expires = datetime.fromisoformat(links["test_link_expires_at"])
    assert timedelta(days=6) < expires - datetime.now(UTC) <= timedelta(days=7)
    assert links["completion"] == {"code": "DONE-7", "redirect_url": "https://recruit.example/done?cc=DONE-7"}
    assert links["screen_out"] == {"code": None, "redirect_url": None}
    assert missing.status_code == 404


def test_a_played_trial_live_its_replay_frames_and_the_answers(server):
    layout = load_layout("practice")

    async def scenario():
        admin = http_client(server.url, headers=ADMIN)
        player = Player(server.url)
        await player.ready(PROLIFIC_PID="p-dash")
        session = await player.session()
        sock = await player.socket()
        hello = await sock.recv()
        while (await sock.recv())["type"] != "state" or sock.received[-1]["tick"] < 3:
            pass
        live = (await admin.get(f"/api/admin/live/{hello['trial']['id']}")).json()
        await sock.send("select_subtask", subtask="pickup_meat")
        end = await play_to_end(sock)
        await sock.close()
        (await player.post("/api/session/questionnaire", {"questionnaire_id": "q", "answers": {"a": 4}})
         ).raise_for_status()
        frames = (await admin.get(f"/api/admin/trials/{hello['trial']['id']}/frames")).json()
        page = (await admin.get(f"/api/admin/trials/{hello['trial']['id']}/frames", params={"start": 0,
                                                                                           "limit": 5})).json()
        rest = (await admin.get(f"/api/admin/trials/{hello['trial']['id']}/frames",
                                params={"start": page["next_start"], "limit": 5000})).json()
        replay = (await admin.get(f"/api/admin/trials/{hello['trial']['id']}")).json()
        answers = (await admin.get(f"/api/admin/participants/{session['participant_id']}/answers")).json()
        unknown = await admin.get("/api/admin/participants/nobody/answers")
        no_trial = await admin.get("/api/admin/trials/999999/frames")
        await admin.aclose()
        await player.close()
        return session, hello, live, end, frames, page, rest, replay, answers, unknown, no_trial

    session, hello, live, end, frames, page, rest, replay, answers, unknown, no_trial = asyncio.run(scenario())
    assert session["fov_angle"] == 100 and hello["fov_angle"] == 100

    grid = live["grid"]
    assert (grid["width"], grid["height"]) == (layout.width, layout.height)
    assert grid["terrain"][0][0] == "counter" and {t for row in grid["terrain"] for t in row} >= {
        "floor", "grill", "board", "sink", "serve", "onion", "meat", "plate"}
    assert live["frame"]["fov"] == live["fov_cells"] == fov_of(layout, live["frame"], 100)
    human = live["world"]["human"]
    assert [live["frame"]["human"]["x"], live["frame"]["human"]["y"]] == human["pos"]
    assert live["frame"]["tick"] == live["tick"] and {"robot", "objects", "stations"} <= set(live["frame"]["kb"])

    assert frames["fov_angle"] == 100 and frames["config_changed"] is False and frames["next_start"] is None
    assert [f["tick"] for f in frames["frames"]] == list(range(end["ticks"] + 1))
    by_tick = {t["tick"]: t for t in replay["ticks"]}
    for f in frames["frames"]:
        assert f["fov"] == fov_of(layout, f, 100)
        if f["tick"] == 0:
            assert f["human_action"] is None and f["kb_gap_total"] == 0
            continue
        stored = by_tick[f["tick"]]
        world = stored["world_state"]
        assert [f["human"]["x"], f["human"]["y"]] == world["human"]["pos"]
        assert [f["robot"]["x"], f["robot"]["y"]] == world["robot"]["pos"]
        assert sorted((o["x"], o["y"], o["object"]) for o in f["objects"]) == sorted(
            (o["pos"][0], o["pos"][1], o["obj"]) for o in world["objects"])
        assert (f["kb_gap"], f["subtask"], f["robot_in_fov"]) == (stored["kb_gap"], stored["subtask"],
                                                                  stored["robot_in_fov"])
        assert f["robot_in_fov"] == ([f["robot"]["x"], f["robot"]["y"]] in f["fov"])
    assert frames["frames"][-1]["orders_left"] == 0 and frames["frames"][-1]["score"] == end["score"]
    assert any(s["state"] != "empty" for f in frames["frames"] for s in f["stations"])

    assert [f["tick"] for f in page["frames"]] == [0, 1, 2, 3, 4, 5] and page["next_start"] == 6
    assert [f["tick"] for f in rest["frames"]] == list(range(6, end["ticks"] + 1))

    [answered] = answers["questionnaires"]
    assert answers["participant_id"] == session["participant_id"]
    assert (answered["questionnaire_id"], answered["after_trial"]) == ("q", 0)
    assert answered["trial_id"] == hello["trial"]["id"]
    assert [(i["id"], i["value"], i["text"], i["scale"]) for i in answered["items"]] == [
        ("a", 4, "A", {"min": 1, "max": 5}), ("b", None, "B", {"min": 1, "max": 5})]
    assert unknown.status_code == 404 and no_trial.status_code == 404
