"""A scripted participant plays whole trials over a real websocket (uvicorn on a TCP port)."""

from __future__ import annotations

import asyncio
import contextlib

from steakhouse_testing import Player, condition_order, play_to_end

from store import trials
from store.tables import TrialRow


def stored_ticks(server, trial_id: int) -> list[int]:
    with server.services.store.transaction() as session:
        return [t.tick for t in trials.ticks(session, trial_id)]


def test_scripted_client_plays_a_whole_trial_to_the_end(live_server, study_file):
    server = live_server([study_file()])

    async def scenario():
        player = Player(server.url)
        await player.ready()
        sock = await player.socket()
        hello = await sock.recv()
        first_state = await sock.recv()
        end = await play_to_end(sock)
        session = await player.session()
        await sock.close()
        await player.close()
        return hello, first_state, end, sock.received, session

    hello, first_state, end, received, session = asyncio.run(scenario())
    assert hello["type"] == "hello" and hello["v"] == 1 and hello["seq"] == 1
    assert hello["tick"] == 0 and hello["resumed"] is False
    assert (hello["width"], hello["height"]) == (15, 10)
    assert "pickup_meat" in hello["subtasks"] and "stop" in hello["interrupts"]
    assert first_state["type"] == "state" and first_state["tick"] == 0
    assert end == {**end, "type": "trial_end", "status": "finished", "reason": "delivered", "delivered": 1,
                   "score": 20, "next": "questionnaire"}
    assert [m["seq"] for m in received] == list(range(1, len(received) + 1))
    states = [m for m in received if m["type"] == "state"]
    assert [s["tick"] for s in states] == list(range(end["ticks"] + 1))
    assert all(m["type"] != "error" for m in received)
    assert session["state"] == "questionnaire"
    trial_id = hello["trial"]["id"]
    assert stored_ticks(server, trial_id) == list(range(1, end["ticks"] + 1))
    with server.services.store.transaction() as session_:
        row = session_.get(TrialRow, trial_id)
        assert (row.status, row.end_reason, row.ticks, row.delivered, row.score) == (
            "finished", "delivered", end["ticks"], 1, 20)
        steps = []
        for t in trials.ticks(session_, trial_id):
            assert t.world_events is not None, f"tick {t.tick} keeps no events"
            steps.append(t.world_events)
    # Every tick keeps what its step did: the one dish was plated, garnished and delivered by somebody.
    kinds = [e["kind"] for events in steps for e in events]
    assert all(set(e) == {"agent", "kind", "pos", "obj"} for events in steps for e in events)
    assert kinds.count("deliver") == 1 and kinds.count("plate_steak") == 1 and kinds.count("garnish") == 1


def test_wait_for_participant_steps_only_when_the_avatar_has_something_to_do(live_server, study_file):
    server = live_server([study_file(timing={"mode": "wait_for_participant", "tick_rate_hz": 30})])

    async def scenario():
        player = Player(server.url)
        await player.ready()
        sock = await player.socket()
        await sock.recv()
        await sock.recv()
        idle = None
        with contextlib.suppress(TimeoutError):  # a round this short is counted down from its start
            idle = await sock.until(lambda m: m["type"] != "countdown", timeout=0.4)
        await sock.send("interrupt", action="down")
        ack = await sock.recv()
        stepped = await sock.until(lambda m: m["type"] == "state")
        try:
            after = await sock.recv(timeout=0.4)
        except TimeoutError:
            after = None
        await sock.send("select_subtask", subtask=stepped["available"][0])
        end = await play_to_end(sock)
        await sock.close()
        await player.close()
        return idle, ack, stepped, after, end

    idle, ack, stepped, after, end = asyncio.run(scenario())
    assert idle is None, "no step may happen while the participant has nothing queued"
    assert ack["type"] == "ack" and ack["queued"] == 1
    assert stepped["tick"] == 1 and stepped["you"]["facing"] == "south"
    assert after is None
    assert end["status"] == "finished"


def test_missed_robot_deadlines_are_logged_and_the_robot_stays(live_server, study_file, monkeypatch):
    from steakhouse_test_robots import slow

    from store.tables import EventRow

    monkeypatch.setenv("STEAKHOUSE_TEST_SLOW_S", "0.1")
    server = live_server([study_file(world={"orders": 1, "horizon": 20, "kb_delay": 1})], robot_factory=slow)

    async def scenario():
        player = Player(server.url)
        await player.ready()
        sock = await player.socket()
        hello = await sock.recv()
        end = await play_to_end(sock)
        await sock.close()
        await player.close()
        return hello, end

    hello, end = asyncio.run(scenario())
    assert end["reason"] == "horizon" and end["ticks"] == 20
    with server.services.store.transaction() as session:
        ticks = trials.ticks(session, hello["trial"]["id"])
        misses = session.query(EventRow).filter_by(trial_id=hello["trial"]["id"], kind="deadline_miss").count()
    # The clock starts once the robot's first decision is in (it may take FIRST_DECISION_S): the first
    # step takes it; every later decision arrives too late and the robot stays.
    assert not ticks[0].robot_missed and ticks[0].robot_action == "north"
    assert all(t.robot_missed and t.robot_action == "stay" for t in ticks[1:])
    assert misses == 19


def test_a_planner_that_cannot_start_gives_a_typed_error_and_the_server_stays_up(live_server, study_file):
    import httpx
    from steakhouse_test_robots import unbuildable

    server = live_server([study_file()], robot_factory=unbuildable)

    async def scenario():
        player = Player(server.url)
        await player.ready()
        sock = await player.socket()
        reply = await sock.recv()
        await sock.close()
        session = await player.session()
        await player.close()
        return reply, session

    reply, session = asyncio.run(scenario())
    assert reply["type"] == "error" and reply["code"] == "internal"
    assert session["state"] == "trial"
    assert httpx.get(server.url + "/healthz").status_code == 200
    assert not server.services.registry.games


def test_a_participant_goes_from_practice_through_every_condition_to_the_end(live_server, study_file):
    server = live_server([study_file(robots=["stay", "fov_aware"], practice=[{"kitchen": "none_3", "robot": "stay"}],
                                     world={"orders": 1, "horizon": 4, "kb_delay": 1},
                                     recruiting={"completion_code": "C0DE"})])

    async def scenario():
        player = Player(server.url)
        joined = await player.join()
        await player.post("/api/session/consent", {"accept": True})
        await player.post("/api/session/instructions_done")
        hellos, states = [], []
        while (session := await player.session())["state"] in ("practice", "trial", "questionnaire"):
            states.append(session["state"])
            if session["state"] == "questionnaire":
                (await player.post("/api/session/questionnaire",
                                   {"questionnaire_id": "q", "answers": {"a": 2}})).raise_for_status()
                continue
            sock = await player.socket()
            hellos.append(await sock.recv())
            await play_to_end(sock)
            await sock.close()
        completion = (await player.http.get("/api/session/completion", headers=player.headers)).json()
        await player.close()
        return joined, hellos, states, session, completion

    joined, hellos, states, session, completion = asyncio.run(scenario())
    assert states == ["practice", "trial", "questionnaire", "trial", "questionnaire"]
    assert [(h["trial"]["kind"], h["trial"]["index"], h["trial"]["number"], h["trial"]["total"]) for h in hellos] == [
        ("practice", 0, 1, 3), ("main", 0, 2, 3), ("main", 1, 3, 3)]
    from study_config import load_layout

    sizes = [(layout.width, layout.height) for layout in (load_layout(k) for k in ("none_3", "practice", "practice"))]
    assert [(h["width"], h["height"]) for h in hellos] == sizes
    assert session["state"] == "done" and completion["code"] == "C0DE"
    order = condition_order(server.services, joined["participant_id"])
    with server.services.store.transaction() as s:
        rows = sorted(s.query(TrialRow).all(), key=lambda r: r.id)
        assert [(r.kind, r.condition_id, r.status, r.end_reason) for r in rows] == [
            ("practice", "stay@none_3", "finished", "horizon")] + [("main", c, "finished", "horizon") for c in order]
        assert len({r.seed for r in rows}) == 3 and {r.config_hash for r in rows} == {
            server.services.catalog.get("tiny").study.config_hash()}


def test_the_shipped_planners_play_through_the_server(live_server, study_file):
    server = live_server([study_file(kitchens=["none_3"], robots=["fov_aware"], timing={"tick_rate_hz": 10},
                                     world={"orders": 1, "horizon": 25, "kb_delay": 3})])

    async def scenario():
        player = Player(server.url)
        await player.ready()
        sock = await player.socket()
        hello = await sock.recv()
        end = await play_to_end(sock)
        await sock.close()
        await player.close()
        return hello, end

    hello, end = asyncio.run(scenario())
    assert end["ticks"] == 25
    with server.services.store.transaction() as session:
        ticks = trials.ticks(session, hello["trial"]["id"])
    decided = [t for t in ticks if not t.robot_missed]
    assert decided and all(t.robot_info is not None and "belief" in t.robot_info for t in decided)
    assert any(t.robot_action != "stay" for t in ticks), "the FOV-aware robot should move"
