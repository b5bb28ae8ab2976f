"""Robots of another package (docs/robots.md) get everything the shipped robots get: the example package's robots
play a study through the server in the robot worker processes (blinded, with the decision deadline and robot
health, in the live view and the replay), and a plug-in that raises, hangs, answers an illegal action or cannot be
imported gives its error or a flagged trial, never a crashed server."""

from __future__ import annotations

import asyncio
import json
from typing import Any

import httpx
import pytest
from steakhouse_testing import Player, play_to_end

from store.tables import EventRow, TickRow, TrialRow
from study_config.study import StudyConfigError, load_study

ADMIN = {"Authorization": "Bearer admin-secret"}


async def play_all(server: Any, watch: bool = False) -> tuple[list[str], list[dict[str, Any]]]:
    """Play every trial of one participant; returns everything the participant received (as text) and, with
    ``watch``, the admin's live view of each trial taken while it ran."""
    player = Player(server.url)
    await player.ready()
    received: list[str] = []
    views: list[dict[str, Any]] = []
    async with httpx.AsyncClient(base_url=server.url, headers=ADMIN) as admin:
        while (session := await player.session())["state"] in ("trial", "questionnaire"):
            received.append(json.dumps(session))
            if session["state"] == "questionnaire":
                (await player.post("/api/session/questionnaire",
                                   {"questionnaire_id": "q", "answers": {"a": 1}})).raise_for_status()
                continue
            sock = await player.socket()
            seen: list[int] = []

            async def look(state: dict[str, Any], sock: Any = sock, seen: list[int] = seen) -> None:
                if watch and not seen and state["tick"] >= 5:
                    trial_id = next(json.loads(m) for m in map(json.dumps, sock.received)
                                    if json.loads(m)["type"] == "hello")["trial"]["id"]
                    seen.append(trial_id)
                    views.append((await admin.get(f"/api/admin/live/{trial_id}")).json())

            await play_to_end(sock, on_state=look)
            await sock.close()
            received += [json.dumps(message) for message in sock.received]
    await player.close()
    return received, views


@pytest.mark.slow
def test_the_example_robots_play_a_study_in_the_workers_blinded_live_and_replayed(live_server, study_file,
                                                                                 example_robots):
    path = study_file(robots=["mylab_scripted", "mylab_learned"], kitchens=["practice"],
                      robot_variants={}, world={"orders": 1, "horizon": 90, "kb_delay": 1},
                      timing={"mode": "fixed_rate", "tick_rate_hz": 10})
    server = live_server([path], robot_workers=1)
    received, views = asyncio.run(play_all(server, watch=True))
    text = "\n".join(received)
    for word in ("mylab", "scripted", "learned", "mylab-robots"):
        assert word not in text, f"the participant's browser received {word!r}"
    assert [v["trial"]["robot"] for v in views] == ["mylab_scripted", "mylab_learned"] or \
        sorted(v["trial"]["robot"] for v in views) == ["mylab_learned", "mylab_scripted"]
    assert all(v["decision"] is not None and v["health"]["decisions"] > 0 for v in views), "the live view"
    with server.services.store.transaction() as session:
        rows = session.query(TrialRow).order_by(TrialRow.id).all()
        assert {(r.robot, r.robot_package, r.robot_version) for r in rows} == {
            ("mylab_scripted", "mylab-robots", "0.1.0"), ("mylab_learned", "mylab-robots", "0.1.0")}
        for row in rows:
            ticks = session.query(TickRow).filter_by(trial_id=row.id).all()
            assert row.status == "finished" and row.decisions == len(ticks) > 0
            assert row.failed_decisions == 0 and all(t.robot_error is None for t in ticks)
            assert any(t.robot_action != "stay" for t in ticks), f"{row.robot} acted"
    for row in rows:
        replay = httpx.get(f"{server.url}/api/admin/trials/{row.id}", headers=ADMIN).json()
        assert len(replay["ticks"]) == row.ticks and replay["trial"]["robot"] == row.robot


@pytest.mark.slow
def test_a_plug_in_that_raises_answers_illegally_or_hangs_flags_its_trial_and_the_server_goes_on(
        live_server, study_file, broken_robots, example_robots):
    order = ["broken_raises@practice", "broken_illegal@practice", "broken_hangs@practice", "mylab_scripted@practice"]
    path = study_file(robots=["broken_raises", "broken_illegal", "broken_hangs", "mylab_scripted"],
                      counterbalancing={"scheme": "fixed", "order": order}, validity={"max_missed_decisions_pct": 50},
                      world={"orders": 1, "horizon": 150, "kb_delay": 1}, timing={"mode": "fixed_rate",
                                                                                   "tick_rate_hz": 20})
    server = live_server([path], robot_workers=1)
    asyncio.run(play_all(server))
    assert httpx.get(server.url + "/healthz").status_code == 200
    with server.services.store.transaction() as session:
        rows = {r.robot: r for r in session.query(TrialRow).all()}
        errors = {robot: [e.payload["message"] for e in session.query(EventRow).filter_by(
            trial_id=row.id, kind="error").all()] for robot, row in rows.items()}
        failed_ticks = {robot: session.query(TickRow).filter(TickRow.trial_id == row.id,
                                                             TickRow.robot_error.is_not(None)).count()
                        for robot, row in rows.items()}
    assert all(row.status == "finished" for row in rows.values())
    raised, illegal, hung, fine = (rows[r] for r in ("broken_raises", "broken_illegal", "broken_hangs",
                                                      "mylab_scripted"))
    assert raised.invalid_reason is not None and "failed" in raised.invalid_reason
    assert errors["broken_raises"][0] == "raised RuntimeError: the lab's planner has a bug"
    # Every decision after the two good ones failed, unless its (failing) answer came after the deadline, which on a
    # loaded machine happens: it then counts as missed. A good one may be missed too, hence the inequalities.
    assert 0 < raised.failed_decisions == failed_ticks["broken_raises"] <= raised.decisions - 2
    assert raised.failed_decisions + (raised.missed_decisions or 0) >= raised.decisions - 2
    assert illegal.invalid_reason is not None and "failed" in illegal.invalid_reason
    assert errors["broken_illegal"][0].startswith("illegal decision: answered the action 'fly', not one of Action.")
    # The hung decision holds its worker until it is stopped, HANG_GRACE_S after its deadline (the next test shows
    # what then): the robot misses its deadlines meanwhile.
    missed = hung.missed_decisions or 0
    assert missed >= hung.decisions - 2 and hung.failed_decisions == 0
    assert hung.invalid_reason == f"robot decisions missed their deadline: {missed} of {hung.decisions} " \
        f"({100 * missed / hung.decisions:.1f} % > 50 %)"
    # The next trial, on the same worker, is played as if nothing had happened.
    assert fine.invalid_reason is None and fine.failed_decisions == 0


def test_a_plug_in_that_cannot_be_imported_stops_the_study_at_validation_with_the_reason(
        study_file, make_settings, broken_robots):
    from server.app import create_app

    path = study_file(robots=["broken_import"])
    with pytest.raises(StudyConfigError) as caught:
        load_study(path)
    (problem,) = caught.value.problems
    assert problem.path == "robots[0]"
    assert problem.reason == (
        "robot 'broken_import' (steakhouse-broken-robots 0.1, steakhouse_broken_robots.unimportable:PLUGIN) cannot "
        "be used: cannot be imported: ModuleNotFoundError: No module named 'steakhouse_no_such_dependency'")
    with pytest.raises(StudyConfigError):
        create_app(make_settings([path]))


def test_a_plug_in_s_variant_settings_are_checked_against_its_declared_settings(study_file, example_robots):
    from study_config.study import validate_study_file

    path = study_file(robots=["patient", "mylab_scripted"], robot_variants={"patient": {
        "planner": "mylab_scripted", "settings": {"first": "fish", "patience": "3", "hands_walk": False}}})
    found = {p.path: p.reason for p in validate_study_file(path)}
    assert found == {
        "robot_variants.patient.settings.first": "Input should be 'meat', 'onion' or 'plate', not 'fish'",
        "robot_variants.patient.settings.patience": "must be an integer, not '3'",
        "robot_variants.patient.settings.hands_walk":
            "unknown setting 'hands_walk' of robot 'mylab_scripted'; its settings: first, patience",
    }
    good = study_file(robots=["patient", "mylab_scripted"], robot_variants={"patient": {
        "planner": "mylab_scripted", "settings": {"first": "plate", "patience": 2}}})
    assert validate_study_file(good) == []


def test_a_hung_decision_is_stopped_in_its_worker_which_then_serves_on(broken_robots, example_robots):
    import time

    from planner.kb import initial_kb
    from planner.robot_catalog import RobotSetup
    from planner.rules import Rules
    from planner.state import initial_state
    from server.robots import ProcessRobots
    from server.robots.worker import HANG_GRACE_S
    from study_config import load_layout

    layout, rules = load_layout("practice"), Rules()
    world = initial_state(layout, rules)

    async def run() -> list[Any]:
        pool = ProcessRobots(1, "planner.robot_catalog:build")
        await pool.start()
        try:
            await pool.open(1, "broken_hangs", layout, rules, RobotSetup(), world, initial_kb(world))
            await pool.open(2, "mylab_scripted", layout, rules, RobotSetup(), world, initial_kb(world))
            choices = [await pool.decide(1, world, (), 1, tick, time.monotonic() + 1.0) for tick in range(3)]
            await asyncio.sleep(HANG_GRACE_S)
            choices.append(await pool.decide(1, world, (), 1, 3, time.monotonic() + 5.0))
            choices.append(await pool.decide(2, world, (), 1, 0, time.monotonic() + 5.0))
            return choices
        finally:
            await pool.shutdown()

    good, also_good, hanging, after, other = asyncio.run(run())
    assert good.error is None and also_good.error is None
    assert hanging.missed
    assert after.failed and after.error is not None and after.error.startswith(
        "raised RobotHung: the robot stands still for the rest of the trial: it hung: the decision of tick 2 was "
        "still running after"), after.error
    assert other.error is None and not other.missed, "the worker serves its other trials again"
