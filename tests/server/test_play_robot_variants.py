"""A study's own robot (``robot_variants``) plays end to end: its trials are played by its planner with its
settings, the store and the export name the variant, and the participant's browser never receives its name."""

from __future__ import annotations

import asyncio
import json
from typing import Any

from steakhouse_testing import Player, play_to_end

from analysis.exports.study_export import read_dataset
from planner.decision import Robot
from planner.layout import Layout
from planner.planner_config import PlannerConfig
from planner.robot_catalog import RobotSetup
from planner.robots import make_robot
from planner.rules import Rules
from store.tables import TrialRow

STUDY = {"robots": ["baseline", "patient_baseline"], "factors": ["robot"],
         "robot_variants": {"patient_baseline": {"planner": "baseline", "settings": {"standoff_ticks": 17}}},
         "world": {"orders": 1, "horizon": 6, "kb_delay": 1}}


def test_a_variant_s_trials_are_played_by_its_planner_with_its_settings_and_it_stays_unnamed(live_server,
                                                                                          study_file):
    opened: list[tuple[str, int]] = []

    def factory(name: str, layout: Layout, rules: Rules, setup: RobotSetup) -> Robot:
        opened.append((name, dict(setup.settings).get("standoff_ticks", PlannerConfig().standoff_ticks)))
        return make_robot("stay", layout, rules)  # what was asked for is recorded; a still robot is fast

    server = live_server([study_file(**STUDY)], robot_factory=factory)

    async def participant() -> list[str]:
        player = Player(server.url)
        await player.ready()
        received: list[str] = []
        while (session := await player.session())["state"] in ("trial", "questionnaire"):
            received.append(json.dumps(session))
            if session["state"] == "questionnaire":
                (await player.post("/api/session/questionnaire",
                                   {"questionnaire_id": "q", "answers": {"a": 1}})).raise_for_status()
                continue
            sock = await player.socket()
            await play_to_end(sock)
            await sock.close()
            received += [json.dumps(message) for message in sock.received]
        await player.close()
        return received

    received = asyncio.run(participant())
    assert sorted(opened) == [("baseline", 5), ("baseline", 17)], "the variant is the baseline planner, standoff 17"
    assert not any("patient" in text for text in received), "the participant never learns which robot it is"
    with server.services.store.transaction() as session:
        stored = {row.robot for row in session.query(TrialRow).all()}
    assert stored == {"baseline", "patient_baseline"}
    trials: Any = read_dataset(server.services.store.engine, "tiny").tables["trials.csv"]
    assert sorted(trials["robot"]) == ["baseline", "patient_baseline"]
