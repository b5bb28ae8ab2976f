"""The admin API: 401 without the admin token (and nothing in the answer), with it studies, participants,
the live trial with its spectator view, flags, and stored trials for replay."""

from __future__ import annotations

import asyncio

import httpx
import pytest
from steakhouse_testing import Player, http_client, play_to_end

from store.tables import TrialRow

ADMIN = {"Authorization": "Bearer admin-secret"}
PATHS = ["/api/admin/studies", "/api/admin/participants", "/api/admin/live", "/api/admin/live/1",
         "/api/admin/trials", "/api/admin/trials/1", "/api/admin/trials/1/events", "/api/admin/robots"]


@pytest.fixture
def server(live_server, study_file):
    return live_server([study_file(robots=["stay", "fov_aware"], world={"orders": 1, "horizon": 300,
                                                                          "kb_delay": 1})])


@pytest.mark.parametrize("headers", [{}, {"Authorization": "Bearer wrong"}, {"Authorization": "admin-secret"},
                                     {"Authorization": "Basic admin-secret"}])
def test_without_the_admin_token_nothing_is_shown(server, headers):
    with httpx.Client(base_url=server.url) as client:
        participant = client.post("/api/studies/tiny/join", json={}).json()
        for path in PATHS:
            response = client.get(path, headers=headers)
            assert response.status_code == 401, path
            assert response.json() == {"detail": {"code": "unauthorized", "message": "a valid token is required"}}
        as_participant = client.get("/api/admin/studies", headers={"Authorization": f"Bearer {participant['token']}"})
        assert as_participant.status_code == 401
        flags = client.post(f"/api/admin/participants/{participant['participant_id']}/flags", json={"test_run": True})
        assert flags.status_code == 401


def test_with_the_token_the_live_trial_and_its_replay_are_listed(server):
    async def scenario():
        admin = http_client(server.url, headers=ADMIN)
        player = Player(server.url)
        await player.ready(PROLIFIC_PID="p-1")
        sock = await player.socket()
        hello = await sock.recv()
        while (await sock.recv())["type"] != "state" or sock.received[-1]["tick"] < 5:
            pass
        live = (await admin.get("/api/admin/live")).json()
        spectator = (await admin.get(f"/api/admin/live/{hello['trial']['id']}")).json()
        studies = (await admin.get("/api/admin/studies")).json()
        people = (await admin.get("/api/admin/participants", params={"study_id": "tiny"})).json()
        await sock.send("select_subtask", subtask="pickup_meat")
        end = await play_to_end(sock)
        await sock.close()
        no_reason = await admin.post(f"/api/admin/participants/{people[0]['participant_id']}/flags",
                                     json={"excluded": True})
        flagged = (await admin.post(f"/api/admin/participants/{people[0]['participant_id']}/flags",
                                    json={"excluded": True, "reason": "fell asleep"})).json()
        studies_after = (await admin.get("/api/admin/studies")).json()
        replay = (await admin.get(f"/api/admin/trials/{hello['trial']['id']}")).json()
        events = (await admin.get(f"/api/admin/trials/{hello['trial']['id']}/events")).json()
        listed = (await admin.get("/api/admin/trials", params={"participant_id": people[0]["participant_id"]})).json()
        gone = await admin.get(f"/api/admin/live/{hello['trial']['id']}")
        await admin.aclose()
        await player.close()
        return hello, live, spectator, studies, people, end, no_reason, flagged, studies_after, replay, events, \
            listed, gone

    (hello, live, spectator, studies, people, end, no_reason, flagged, studies_after, replay, events, listed,
     gone) = asyncio.run(scenario())
    trial_id = hello["trial"]["id"]
    assert [t["trial_id"] for t in live] == [trial_id] and live[0]["connected"] is True
    assert live[0]["participant"] == people[0]["participant_id"] and live[0]["robot"] == "stay"
    assert spectator["tick"] >= 5 and spectator["world"]["tick"] == spectator["tick"]
    assert spectator["layout"]["rows"][0].startswith("XXXX")
    assert [spectator["world"]["human"]["pos"][0], spectator["world"]["human"]["pos"][1]] in spectator["fov_cells"]
    assert set(spectator["kb_gap"]) == {"grill", "board", "sink", "robot_held"}
    assert {"kb", "kb_summary", "world_summary", "decision", "lateness_ms", "deadline_misses"} <= set(spectator)
    assert spectator["lateness_ms"]["count"] >= 5
    [study] = studies
    assert study["id"] == "tiny" and [o["conditions"] for o in study["orders"]] == [
        ["stay@practice", "fov_aware@practice"], ["fov_aware@practice", "stay@practice"]]
    assert [o["counted"] for o in study["orders"]] == [1, 0] and study["live_trials"] == 1
    assert people[0]["recruiting"] == {"PROLIFIC_PID": "p-1"} and people[0]["state"] == "trial"
    assert no_reason.status_code == 422
    assert flagged["excluded"] is True and flagged["exclusion_reason"] == "fell asleep"
    assert [o["counted"] for o in studies_after[0]["orders"]] == [0, 0]
    assert [o["excluded"] for o in studies_after[0]["orders"]] == [1, 0]
    assert replay["trial"]["status"] == "finished" and replay["initial_state"]["tick"] == 0
    assert [t["tick"] for t in replay["ticks"]] == list(range(1, end["ticks"] + 1))
    assert replay["ticks"][-1]["world_state"]["orders_left"] == 0
    assert {"select_subtask", "connect", "trial_start", "trial_end"} <= {e["kind"] for e in events}
    assert [t["trial_id"] for t in listed] == [trial_id]
    with server.services.store.transaction() as session:
        stored_seed = session.get(TrialRow, trial_id).seed
    assert listed[0]["seed"] == replay["trial"]["seed"] == str(stored_seed), "as text: JavaScript keeps 53 bits"
    assert live[0]["seed"] == spectator["trial"]["seed"] == str(stored_seed)
    assert gone.status_code == 404
