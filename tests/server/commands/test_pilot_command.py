"""``steakhouse pilot`` end to end: simulated participants through the real server's REST flow and websocket,
stored as pilot participants, left out of exports unless asked; what they did follows from the frames alone."""

from __future__ import annotations

import asyncio

import pandas as pd
import pytest
from sqlalchemy import create_engine, select
from steakhouse_test_robots import simulated_partner

from analysis.exports.study_export import read_dataset
from pilot.client import Seat, respond, trial_rng
from pilot.config import ParticipantConfig
from pilot.mind import WAIT_REASONS, Mind, belief_of, told_refused
from pilot.perception import Perception
from pilot.run import run_pilot
from planner.fov import view
from planner.geometry import Direction
from planner.subtasks import Subtask
from server.cli import main
from store.tables import AnswerRow, ParticipantRow, TrialRow
from study_config.catalog import load_one

SCRIPTED_ROBOT = {"max_robot_flickers": 1000}
"""The robot here is the simulated human's model (``simulated_partner``), not a planner: it may put an item down and
pick it up again, which robot health would count as flickers (docs/operations.md, "Robot health") and leave the
trial out of the cells; these tests are about the pilot's flow, not the robot."""
QUIZ = {"max_attempts": 2, "questions": [{"id": "q1", "text": "?", "options": ["a", "b"], "answer": 2,
                                    "explanation": "b"}]}


@pytest.fixture
def piloted(live_server, study_file, db_url):
    path = study_file(kitchens=["none_3"], robots=["stay", "baseline"], quiz=QUIZ,
                      practice=[{"kitchen": "practice", "robot": "stay", "count": 1}],
                      world={"orders": 1, "horizon": 60, "kb_delay": 2}, timing={"tick_rate_hz": 5},
                      validity=SCRIPTED_ROBOT)
    server = live_server([path], robot_factory=simulated_partner)
    loaded = load_one(path)
    seat = Seat(server.url, "admin-secret", loaded, ParticipantConfig(), keep_frames=True)
    result = asyncio.run(run_pilot(seat, 3, 2, seed=5))
    return server, loaded, result, db_url


def test_a_pilot_goes_through_the_flow_is_marked_and_is_exported_only_when_asked(piloted, tmp_path) -> None:
    server, loaded, result, db_url = piloted
    assert not result.failures
    assert len(result.outcomes) == 3 and all(o.completed for o in result.outcomes)
    assert all(o.trials == 3 for o in result.outcomes), "practice and both rounds"
    with server.services.store.transaction() as session:
        people = session.scalars(select(ParticipantRow)).all()
        assert {(p.pilot, p.pilot_pace, p.status) for p in people} == {(True, "fast", "completed")}
        assert session.query(TrialRow).filter(TrialRow.status == "finished").count() == 9
        assert session.query(AnswerRow).count() > 0
        invalid = session.query(TrialRow).filter(TrialRow.invalid_reason.is_not(None)).count()
        low = session.query(TrialRow).filter(TrialRow.engagement_reason.is_not(None)).count()
    assert (result.invalid_trials, result.low_engagement_trials) == (invalid, low), "the summary counts them"
    _exports_leave_pilots_out_unless_asked(loaded.id, db_url, tmp_path)


def test_what_it_sent_follows_from_the_masked_frames_alone(piloted) -> None:
    """Each frame it got shows only the cells in its view; replaying those frames offline (no server) with
    the trial's generator — the states, and the refusals it reads — gives back every message it sent."""
    _, loaded, result, _ = piloted
    world = loaded.study.world
    replayed = 0
    for _index, outcome in enumerate(sorted(result.outcomes, key=lambda o: o.name)):
        for trial, (frames, sent) in enumerate(zip(outcome.frames, outcome.sent, strict=True)):
            hello = frames[0]
            seen = Perception(hello["width"], hello["height"], tuple(loaded.layouts.values()))
            mind, rng = Mind(), trial_rng((5, int(outcome.name.rsplit("-", 1)[1]) - 1), trial)
            bodies = iter(sent)
            for frame in frames:
                if frame["type"] == "blocked" and frame["ended"] and frame["subtask"] and seen.kb is not None \
                        and frame["reason"] not in WAIT_REASONS:
                    refused = Subtask(frame["subtask"])
                    mind = told_refused(mind, refused, belief_of(seen.layout, loaded.rules, seen.kb, refused))
                if frame["type"] != "state":
                    continue
                body = next(bodies, None)
                if body is None:
                    break
                you = frame["you"]
                shown = {(c["x"], c["y"]) for c in frame["cells"]}
                layout = seen.observe(frame, world.fov_angle, world.kb_delay).layout
                assert shown == set(view(layout, (you["x"], you["y"]), Direction(you["facing"]),
                                         world.fov_angle).cells)
                seen, mind, again = respond(mind, seen, frame, dict(hello["needs"]), loaded, ParticipantConfig(), rng)
                assert again == body
                replayed += 1
    assert replayed > 50


def _exports_leave_pilots_out_unless_asked(study_id: str, db_url: str, tmp_path) -> None:
    engine = create_engine(db_url)
    try:
        plain = read_dataset(engine, study_id)
        assert plain.tables["participants.csv"].empty and plain.tables["cells.csv"].empty
        assert plain.tables["answers.csv"].empty
        with_pilots = read_dataset(engine, study_id, include_pilot=True)
        people = with_pilots.tables["participants.csv"]
        assert len(people) == 3 and set(people["pilot"]) == {1}
        assert len(with_pilots.tables["cells.csv"]) == 6
    finally:
        engine.dispose()
    out = tmp_path / "results"
    assert main(["analyze", "--study", study_id, "--database-url", db_url, "--out", str(out), "--no-plots",
                 "--dv", "ticks,interrupts", "--include-pilot"]) == 0
    assert (out / "anova.csv").is_file()
    power = tmp_path / "power"
    assert main(["power", "--study", study_id, "--database-url", db_url, "--n", "4,8", "--simulations", "50",
                 "--dv", "ticks,interrupts", "--no-plots", "--out", str(power)]) == 0
    table = pd.read_csv(power / "power.csv")
    assert set(table["n"]) == {4, 8} and set(table["measure"]) == {"ticks", "interrupts"}
    assert table["power"].between(0, 1).all() and (table["pilot_n"] == 3).all()


def test_the_summary_says_how_many_trials_the_analysis_leaves_out() -> None:
    from server.commands.pilot import health_summary

    assert health_summary(0, 0) == "0 robot-invalid, 0 low-engagement"
    assert health_summary(2, 1) == ("2 robot-invalid, 1 low-engagement: left out of the analysis unless "
                                    "--include-invalid")
    assert "not counted" in health_summary(None, None)


@pytest.mark.store_agnostic
def test_power_of_a_pilot_with_the_view_between_participants(live_server, study_file, tmp_path, capsys) -> None:
    """A mixed design's pilot gets the mixed ANOVA's tests at each total n; a chosen effect size, simulated for
    designs within participants only, is refused with the reason."""
    path = study_file("between_view", kitchens=["none_3"], robots=["stay", "baseline"], factors=["robot"],
                      views=["top_down", "first_person"], between=["view"],
                      world={"orders": 1, "horizon": 60, "kb_delay": 2}, validity=SCRIPTED_ROBOT)
    server = live_server([path], robot_factory=simulated_partner)
    loaded = load_one(path)
    result = asyncio.run(run_pilot(Seat(server.url, "admin-secret", loaded, ParticipantConfig()), 6, 3, seed=2))
    assert not result.failures and all(o.completed for o in result.outcomes)
    url = server.services.store.engine.url.render_as_string(hide_password=False)
    out = tmp_path / "power"
    assert main(["power", "--study", "between_view", "--database-url", url, "--n", "4,8", "--simulations", "20",
                 "--dv", "ticks", "--no-plots", "--out", str(out)]) == 0
    table = pd.read_csv(out / "power.csv")
    assert list(dict.fromkeys(table["test"])) == ["view", "robot", "view * robot"]
    assert set(table["n"]) == {4, 8} and table["power"].between(0, 1).all() and (table["pilot_n"] == 6).all()
    assert "view is between participants" in (out / "power.md").read_text(encoding="utf-8")
    capsys.readouterr()
    assert main(["power", "--study", "between_view", "--database-url", url, "--n", "8", "--effect", "eta2g=0.1",
                 "--out", str(tmp_path / "refused")]) == 2
    assert "within participants only" in capsys.readouterr().err
