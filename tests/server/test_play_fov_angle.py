"""The field of view as a factor end to end: each participant of a ``between: [fov_angle]`` study plays (and
practises) at their group's angle, the robot's model of the person has that angle, the trial row records it, the
admin's replay draws it, the export carries it, and the participant is told the angle as a number they see anyway
(``fov_angle`` in the session and ``hello``), never as a condition."""

from __future__ import annotations

import asyncio
from typing import Any

import httpx
from steakhouse_testing import Player, condition_order, play_every_trial

from analysis.exports.study_export import read_dataset
from planner import robot_catalog
from planner.decision import Robot
from planner.layout import Layout
from planner.robot_catalog import RobotSetup
from planner.rules import Rules
from store.tables import TrialRow

STUDY = {"robots": ["stay"], "kitchens": ["practice"], "fov_angles": [90, 150], "between": ["fov_angle"],
         "factors": ["robot"], "practice": [{"kitchen": "practice", "robot": "stay"}],
         "world": {"orders": 1, "horizon": 6, "kb_delay": 1}}


def test_each_group_plays_practises_and_is_modelled_at_its_own_angle(live_server, study_file):
    modelled: list[float] = []

    def factory(name: str, layout: Layout, rules: Rules, setup: RobotSetup) -> Robot:
        modelled.append(setup.person.fov_angle)
        return robot_catalog.build(name, layout, rules, setup)

    server = live_server([study_file(**STUDY)], robot_factory=factory)

    async def participant() -> tuple[str, list[float], list[dict[str, Any]], dict[str, Any]]:
        player = Player(server.url)
        joined = await player.join()
        told = (await player.session())["fov_angle"]
        await player.post("/api/session/consent", {"accept": True})
        await player.post("/api/session/instructions_done")
        played = await play_every_trial(player)
        await player.close()
        return joined["participant_id"], [told, *(h["fov_angle"] for _, h in played)], [h for _, h in played], \
            played[0][0]

    async def scenario():
        return [await participant() for _ in range(2)]

    results = asyncio.run(scenario())
    angles = {}
    for public_id, told, hellos, first_trial in results:
        (cid,) = condition_order(server.services, public_id)
        angle = float(cid.rsplit("@", 1)[1])
        angles[public_id] = angle
        assert told == [angle, angle, angle], "session, practice hello and main hello all at the group's angle"
        assert all("condition" not in h and "group" not in h for h in hellos)
        assert "fov_angle" not in first_trial, "the round card names no condition"
    assert sorted(angles.values()) == [90.0, 150.0], "the two joins fill both groups"
    assert modelled == [a for a in angles.values() for _ in range(2)], "each trial's robot models its angle"
    with server.services.store.transaction() as s:
        rows = sorted(s.query(TrialRow).all(), key=lambda r: r.id)
        assert [r.fov_angle for r in rows] == modelled
        main_ids = {r.id: r.fov_angle for r in rows if r.kind == "main"}
    for trial_id, angle in main_ids.items():
        frames = httpx.get(f"{server.url}/api/admin/trials/{trial_id}/frames",
                           headers={"Authorization": "Bearer admin-secret"}).json()
        assert frames["fov_angle"] == frames["trial"]["fov_angle"] == angle
    dataset = read_dataset(server.services.store.engine, "tiny")
    assert sorted(dataset.tables["trials.csv"]["fov_angle"]) == [90, 90, 150, 150]
    cells = dataset.tables["cells.csv"]
    assert sorted(zip(cells["condition"], cells["fov_angle"], strict=True)) == [
        ("stay@practice@150", 150), ("stay@practice@90", 90)]
    assert set(dataset.tables["ticks.csv"]["fov_angle"]) == {90, 150}
