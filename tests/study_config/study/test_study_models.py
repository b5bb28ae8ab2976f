"""The shipped studies, the documented defaults, conditions, and the config hash stored with each trial."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from pydantic import ValidationError

from study_config.study import Study, load_study, validate_study_file

ROOT = Path(__file__).resolve().parents[3]
STUDY_CONFIG = ROOT / "study_config"

MINIMAL = "id: t\ntitle: T\nkitchens: [none_3, mid_2]\nrobots: [fov_aware, baseline]\n"


def write(tmp_path: Path, text: str, name: str = "study.yaml") -> Path:
    path = tmp_path / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize("name", ["paper_study.yaml", "demo.yaml"])
def test_shipped_studies_validate(name: str) -> None:
    assert validate_study_file(STUDY_CONFIG / name) == []


def test_paper_study_is_the_papers_design() -> None:
    study = load_study(STUDY_CONFIG / "paper_study.yaml")
    assert [c.id for c in study.conditions] == [
        "fov_aware@none_3", "fov_aware@mid_2", "baseline@none_3", "baseline@mid_2"]
    orders = study.condition_orders()
    assert len(orders) == 4 and {o[0] for o in orders} == {c.id for c in study.conditions}
    assert [(p.kitchen.name, p.robot, p.count) for p in study.practice] == [("practice", "stay", 1)]
    # kb_delay 1: the 2D study's delay
    assert (study.world.fov_angle, study.world.kb_delay, study.timing.tick_rate_hz) == (120, 1, 5)
    (questionnaire,) = study.questionnaires
    assert questionnaire.when == "after_each_trial"
    ratings = [i for i in questionnaire.items if i.type == "rating"]
    assert len(ratings) == 5
    assert all(i.scale is not None and (i.scale.min, i.scale.max) == (1, 7) for i in ratings)
    assert any("knew what the robot was doing" in i.text for i in ratings)
    assert [i.id for i in ratings if i.reverse] == ["workload"]
    (comment,) = [i for i in questionnaire.items if i.type == "text"]
    assert not comment.required
    (scale,) = questionnaire.scales
    assert set(scale.items) == {i.id for i in ratings}
    assert study.quiz is not None and [q.id for q in study.quiz.questions] == [
        "black_cells", "cancel_task", "robot_sees"]


def test_demo_is_short() -> None:
    study = load_study(STUDY_CONFIG / "demo.yaml")
    assert len(study.conditions) == 2 and len(study.kitchens) == 1
    assert (study.world.orders, study.world.horizon) == (1, 150)
    assert study.practice == ()
    assert [len(q.items) for q in study.questionnaires] == [2]


def test_omitted_settings_take_the_documented_defaults(tmp_path: Path) -> None:
    study = load_study(write(tmp_path, MINIMAL))
    world = study.world
    assert (world.fov_angle, world.kb_delay, world.orders, world.horizon) == (120, 3, 2, 400)
    assert (world.cook_time, world.chop_time, world.wash_time, world.delivery_reward) == (10, 2, 2, 20)
    assert (study.timing.mode, study.timing.tick_rate_hz) == ("fixed_rate", 5)
    assert study.counterbalancing.scheme == "latin_square"
    assert study.factors == ("robot", "kitchen")
    assert study.practice == () and study.questionnaires == ()
    assert (study.reconnect.grace_seconds, study.reconnect.after_grace) == (60, "abandon")
    assert study.assignment.in_progress_window_minutes == 30
    assert study.recruiting.url_parameters == ("PROLIFIC_PID", "STUDY_ID", "SESSION_ID")
    assert study.test_run is False
    assert "consent" in study.consent.lower() and "black" in study.instructions.lower()


def test_first_factor_varies_slowest(tmp_path: Path) -> None:
    study = load_study(write(tmp_path, MINIMAL + "factors: [kitchen, robot]\n"))
    assert [c.id for c in study.conditions] == [
        "fov_aware@none_3", "baseline@none_3", "fov_aware@mid_2", "baseline@mid_2"]


def test_fixed_counterbalancing_gives_everyone_that_order(tmp_path: Path) -> None:
    order = ["baseline@mid_2", "fov_aware@none_3", "baseline@none_3", "fov_aware@mid_2"]
    text = MINIMAL + f"counterbalancing: {{scheme: fixed, order: [{', '.join(order)}]}}\n"
    study = load_study(write(tmp_path, text))
    assert study.condition_orders() == [tuple(order)]


def test_completion_redirect_fills_in_the_code(tmp_path: Path) -> None:
    text = MINIMAL + "recruiting:\n  completion_code: C0FFEE\n" \
        "  completion_redirect_url: https://app.prolific.com/submissions/complete?cc={code}\n"
    study = load_study(write(tmp_path, text))
    expected = "https://app.prolific.com/submissions/complete?cc=C0FFEE"
    assert study.recruiting.redirect("completion") == expected
    assert study.recruiting.redirect("screen_out") is None


def test_study_is_frozen() -> None:
    study = load_study(STUDY_CONFIG / "demo.yaml")
    with pytest.raises(ValidationError):
        study.world = study.world


def test_config_hash_is_stable_across_loads_and_processes() -> None:
    path = STUDY_CONFIG / "paper_study.yaml"
    digest = load_study(path).config_hash()
    assert len(digest) == 64 and int(digest, 16) >= 0
    assert load_study(path).config_hash() == digest
    code = "import sys; from study_config.study import load_study; print(load_study(sys.argv[1]).config_hash())"
    other = subprocess.run(
        [sys.executable, "-c", code, str(path)], cwd=ROOT, capture_output=True, text=True, check=True,
        env={"PYTHONHASHSEED": "12345", "PATH": ""},
    )
    assert other.stdout.strip() == digest


def test_config_hash_ignores_how_the_yaml_is_written(tmp_path: Path) -> None:
    block_text = MINIMAL + "timing:\n  tick_rate_hz: 5\nworld:\n  orders: 2\n"
    block = load_study(write(tmp_path, block_text, "a.yaml"))
    flow = "robots: [fov_aware, baseline]\nworld: {orders: 2}\ntiming: {tick_rate_hz: 5.0}\n" \
        "kitchens: [none_3, mid_2]\ntitle: T\nid: t  # same study\n"
    assert load_study(write(tmp_path, flow, "b.yaml")).config_hash() == block.config_hash()


def test_config_hash_does_not_depend_on_where_the_files_are(tmp_path: Path) -> None:
    shutil.copy(STUDY_CONFIG / "layouts" / "none_3.layout", tmp_path / "mine.layout")
    text = MINIMAL.replace("[none_3, mid_2]", "[mine.layout, mid_2]")
    here = load_study(write(tmp_path, text)).config_hash()
    moved = tmp_path / "elsewhere"
    moved.mkdir()
    shutil.copy(tmp_path / "mine.layout", moved / "mine.layout")
    assert load_study(write(moved, text)).config_hash() == here


@pytest.mark.parametrize(
    "change",
    [
        "world: {fov_angle: 90}\n",
        "world: {kb_delay: 1}\n",
        "timing: {tick_rate_hz: 4}\n",
        "timing: {mode: wait_for_participant}\n",
        "counterbalancing: full\n",
        "reconnect: {after_grace: restart}\n",
        "test_run: true\n",
        "practice: [{kitchen: practice, robot: stay}]\n",
        "questionnaires: [{id: q, items: [{id: a, text: Other text., scale: {min: 1, max: 7}}]}]\n",
    ],
)
def test_config_hash_changes_when_a_setting_changes(tmp_path: Path, change: str) -> None:
    base = load_study(write(tmp_path, MINIMAL, "base.yaml")).config_hash()
    assert load_study(write(tmp_path, MINIMAL + change, "changed.yaml")).config_hash() != base


def test_config_hash_changes_when_a_question_is_reworded(tmp_path: Path) -> None:
    q = "questionnaires: [{id: q, items: [{id: a, text: %s, scale: {min: 1, max: 7}}]}]\n"
    first = load_study(write(tmp_path, MINIMAL + q % "I trusted it.", "a.yaml")).config_hash()
    second = load_study(write(tmp_path, MINIMAL + q % "I trusted the robot.", "b.yaml")).config_hash()
    assert first != second


def test_config_hash_changes_when_a_kitchen_file_changes(tmp_path: Path) -> None:
    layout = tmp_path / "mine.layout"
    shutil.copy(STUDY_CONFIG / "layouts" / "none_3.layout", layout)
    path = write(tmp_path, MINIMAL.replace("[none_3, mid_2]", "[mine.layout, mid_2]"))
    before = load_study(path).config_hash()
    layout.write_text(layout.read_text() + "\n")  # the same grid, other bytes: still a change of the study
    assert load_study(path).config_hash() != before


def test_models_validate_without_a_file() -> None:
    study = Study.model_validate({"id": "t", "title": "T", "kitchens": ["none_3"], "robots": ["stay"]})
    assert [c.id for c in study.conditions] == ["stay@none_3"]
    assert study.kitchen("none_3").path.name == "none_3.layout"


def test_resolved_study_round_trips_through_json() -> None:
    study = load_study(STUDY_CONFIG / "paper_study.yaml")
    again = Study.model_validate_json(study.model_dump_json())
    assert again == study
    assert again.config_hash() == study.config_hash()
