"""Invalid study files are refused with every problem named by file, field path and reason."""

from __future__ import annotations

import shutil
import textwrap
from pathlib import Path

import pytest

from study_config.study import StudyConfigError, StudyProblem, load_study, validate_study_file

LAYOUTS = Path(__file__).resolve().parents[3] / "study_config" / "layouts"

BASE = """\
id: t
title: A test study
kitchens: [none_3, mid_2]
robots: [fov_aware, baseline]
"""

QUESTIONNAIRE = """\
questionnaires:
  - id: post
    items:
      - {id: fluency, text: Fluent., scale: {min: 1, max: 7}}
      - {id: trust, text: Trust., scale: {min: 1, max: 7}}
"""


def write(tmp_path: Path, text: str, name: str = "study.yaml") -> Path:
    path = tmp_path / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(textwrap.dedent(text), encoding="utf-8")
    return path


def kitchens(entries: str) -> str:
    return BASE.replace("[none_3, mid_2]", entries)


def robots(entries: str) -> str:
    return BASE.replace("[fov_aware, baseline]", entries)


def problems_of(tmp_path: Path, text: str) -> dict[str, str]:
    found = validate_study_file(write(tmp_path, text))
    assert found, "the study should be invalid"
    return {p.path: p.reason for p in found}


CASES = {
    "unknown kitchen": (
        kitchens("[none_3, atlantis]"), "kitchens[1]", "unknown kitchen 'atlantis'"),
    "missing kitchen file": (
        kitchens("[none_3, mine/corridor.layout]"), "kitchens[1]", "no kitchen file"),
    "unknown robot": (
        robots("[fov_aware, terminator]"), "robots[1]", "unknown robot 'terminator'"),
    "duplicate kitchen": (
        kitchens("[none_3, mid_2, none_3]"), "kitchens[2]", "duplicate kitchen 'none_3'"),
    "duplicate robot": (
        robots("[baseline, baseline]"), "robots[1]", "duplicate robot 'baseline'"),
    "duplicate item id": (
        BASE + QUESTIONNAIRE.replace("id: trust", "id: fluency"),
        "questionnaires[0].items[1].id", "duplicate item id 'fluency'"),
    "duplicate questionnaire id": (
        BASE + QUESTIONNAIRE + QUESTIONNAIRE.replace("questionnaires:\n", ""),
        "questionnaires[1].id", "duplicate questionnaire id 'post'"),
    "unknown scheme": (
        BASE + "counterbalancing: random\n", "counterbalancing.scheme", "'latin_square', 'full' or 'fixed'"),
    "fixed without order": (
        BASE + "counterbalancing: fixed\n", "counterbalancing.order", "needs an order"),
    "fixed order missing a condition": (
        BASE + "counterbalancing:\n  scheme: fixed\n"
               "  order: [fov_aware@none_3, fov_aware@mid_2, baseline@mid_2]\n",
        "counterbalancing.order", "missing conditions: baseline@none_3"),
    "fixed order with an unknown condition": (
        BASE + "counterbalancing: {scheme: fixed, order: [fov_aware@none_3, stay@none_3]}\n",
        "counterbalancing.order[1]", "unknown condition 'stay@none_3'"),
    "fixed order repeating a condition": (
        BASE + "counterbalancing:\n  scheme: fixed\n  order: [fov_aware@none_3, fov_aware@mid_2,"
               " baseline@none_3, fov_aware@none_3]\n",
        "counterbalancing.order[3]", "duplicate condition 'fov_aware@none_3'"),
    "order with a non-fixed scheme": (
        BASE + "counterbalancing: {scheme: full, order: [fov_aware@none_3]}\n",
        "counterbalancing.order", "only used with scheme 'fixed'"),
    "missing questionnaire scale": (
        BASE + QUESTIONNAIRE + "      - {id: legibility, text: Legible.}\n",
        "questionnaires[0].items[2].scale", "required field is missing"),
    "empty scale": (
        BASE + QUESTIONNAIRE.replace("id: trust, text: Trust., scale: {min: 1, max: 7}",
                                     "id: trust, text: Trust., scale: {min: 5, max: 5}"),
        "questionnaires[0].items[1].scale.max", "must be greater than min"),
    "label outside the scale": (
        BASE + QUESTIONNAIRE.replace("{min: 1, max: 7}}\n", "{min: 1, max: 7, labels: {8: Too high}}}\n", 1),
        "questionnaires[0].items[0].scale.labels[8]", "outside 1..7"),
    "number given as text": (
        BASE + "world: {horizon: lots}\n", "world.horizon", "valid integer"),
    "list given as one value": (
        robots("fov_aware"), "robots", "should be a list"),
    "mapping given as a value": (
        BASE + "timing: 5\n", "timing", "should be a mapping"),
    "boolean given as text": (
        BASE + "test_run: maybe\n", "test_run", "valid boolean"),
    "label read as a boolean": (
        BASE + QUESTIONNAIRE.replace("{min: 1, max: 7}}\n", "{min: 1, max: 7, labels: {1: no}}}\n", 1),
        "questionnaires[0].items[0].scale.labels[1]", "quote"),
    "out of range number": (
        BASE + "world: {fov_angle: 400}\n", "world.fov_angle", "less than or equal to 360"),
    "unknown timing mode": (
        BASE + "timing: {mode: turbo}\n", "timing.mode", "'fixed_rate' or 'wait_for_participant'"),
    "unknown field": (
        BASE + "wrld: {orders: 3}\n", "wrld", "unknown field; did you mean 'world'?"),
    "unknown practice robot": (
        BASE + "practice: [{kitchen: practice, robot: statue}]\n",
        "practice[0].robot", "unknown robot 'statue'"),
    "unknown after_grace": (
        BASE + "reconnect: {after_grace: later}\n",
        "reconnect.after_grace", "'resume', 'restart' or 'abandon'"),
    "redirect with another placeholder": (
        BASE + "recruiting:\n  completion_code: ABC\n"
               "  completion_redirect_url: https://x.org/?cc={code}&p={pid}\n",
        "recruiting.completion_redirect_url", "only placeholder allowed is {code}"),
    "redirect code without a code": (
        BASE + "recruiting: {completion_redirect_url: 'https://x.org/?cc={code}'}\n",
        "recruiting.completion_code", "no code is set"),
    "study id not a slug": (
        BASE.replace("id: t", "id: My Study"), "id", "not a valid id"),
    "no robots": (
        robots("[]"), "robots", "at least one"),
    "missing title": (
        BASE.replace("title: A test study\n", ""), "title", "required field is missing"),
    "two kitchens without the kitchen factor": (
        BASE + "factors: [robot]\n", "factors", "kitchens has 2 entries but 'kitchen' is not a factor"),
    "key written twice": (
        BASE + "world: {orders: 1}\nworld: {orders: 2}\n", "world", "written more than once"),
}


@pytest.mark.parametrize("text, path, reason", CASES.values(), ids=CASES.keys())
def test_invalid_study_names_the_field(tmp_path: Path, text: str, path: str, reason: str) -> None:
    found = problems_of(tmp_path, text)
    assert path in found, found
    assert reason in found[path]


def test_every_problem_is_reported_at_once(tmp_path: Path) -> None:
    text = BASE.replace("[none_3, mid_2]", "[none_3, atlantis]").replace("baseline", "terminator")
    text += "world: {horizon: lots}\n" + QUESTIONNAIRE + "      - {id: legibility, text: Legible.}\n"
    path = write(tmp_path, text)
    with pytest.raises(StudyConfigError) as info:
        load_study(path)
    paths = [p.path for p in info.value.problems]
    assert paths == ["kitchens[1]", "robots[1]", "world.horizon", "questionnaires[0].items[2].scale"]
    message = str(info.value)
    assert len(message.splitlines()) == 4
    assert f"{path}: robots[1]: unknown robot 'terminator'" in message


def test_problem_reads_file_field_reason_and_line(tmp_path: Path) -> None:
    path = write(tmp_path, BASE + "world:\n  orders: 2\n  horizon: lots\n")
    (problem,) = validate_study_file(path)
    assert problem == StudyProblem(str(path), "world.horizon", problem.reason, 7)
    assert str(problem).startswith(f"{path}: world.horizon: should be a valid integer")
    assert str(problem).endswith("(line 7)")


def test_malformed_yaml_reports_line_and_column(tmp_path: Path) -> None:
    path = write(tmp_path, "id: t\ntitle: T\nkitchens: [none_3, mid_2\nrobots: [fov_aware]\n")
    (problem,) = validate_study_file(path)
    assert problem.path == ""
    assert "invalid YAML at line 4, column 7" in problem.reason
    assert str(problem).startswith(f"{path}: invalid YAML")


@pytest.mark.parametrize("text, found", [("", "the file is empty"), ("- a\n- b\n", "found a list")])
def test_a_study_must_be_a_mapping(tmp_path: Path, text: str, found: str) -> None:
    (problem,) = validate_study_file(write(tmp_path, text))
    assert "must be a mapping of fields" in problem.reason and found in problem.reason


def test_missing_file_is_a_problem_not_a_crash(tmp_path: Path) -> None:
    (problem,) = validate_study_file(tmp_path / "nope.yaml")
    assert "cannot read the file" in problem.reason


def test_yaml_tags_cannot_build_python_objects(tmp_path: Path) -> None:
    path = write(tmp_path, BASE + "notes: !!python/object/apply:os.system ['echo hacked']\n")
    (problem,) = validate_study_file(path)
    assert "invalid YAML" in problem.reason


def test_kitchen_by_path_relative_to_the_study(tmp_path: Path) -> None:
    shutil.copy(LAYOUTS / "none_3.layout", tmp_path / "corridor.layout")
    path = write(tmp_path, BASE.replace("[none_3, mid_2]", "[../corridor.layout, mid_2]"), "studies/s.yaml")
    study = load_study(path)
    assert [k.name for k in study.kitchens] == ["corridor", "mid_2"]
    assert study.kitchens[0].path == (tmp_path / "corridor.layout").resolve()
    assert study.conditions[0].id == "fov_aware@corridor"


def test_kitchen_path_and_name_may_not_collide(tmp_path: Path) -> None:
    shutil.copy(LAYOUTS / "mid_1.layout", tmp_path / "none_3.layout")
    found = problems_of(tmp_path, BASE.replace("[none_3, mid_2]", "[none_3, ./none_3.layout]"))
    assert "duplicate kitchen 'none_3'" in found["kitchens[1]"]


def test_a_kitchen_name_too_long_to_store_is_refused_before_any_trial(tmp_path: Path) -> None:
    # The store keeps the kitchen's name with every trial (64 characters; PostgreSQL refuses more).
    fits, too_long = "k" * 64, "k" * 65
    for stem in (fits, too_long):
        shutil.copy(LAYOUTS / "none_3.layout", tmp_path / f"{stem}.layout")
    assert [k.name for k in load_study(write(tmp_path, BASE.replace("[none_3, mid_2]", f"[./{fits}.layout, mid_2]"))
                                       ).kitchens] == [fits, "mid_2"]
    found = problems_of(tmp_path, BASE.replace("[none_3, mid_2]", f"[./{too_long}.layout, mid_2]"))
    assert found == {"kitchens[0]": f"kitchen file name '{too_long}.layout': at most 64 characters before .layout "
                                    "(the name is stored with every trial)"}


def test_an_id_too_long_to_store_is_refused(tmp_path: Path) -> None:
    # Study, questionnaire and item ids are stored in 64-character columns (PostgreSQL refuses more).
    too_long = BASE.replace("id: t\n", f"id: {'s' * 65}\n") + QUESTIONNAIRE.replace("id: trust", f"id: {'t' * 65}")
    assert problems_of(tmp_path, too_long) == {
        "id": "an id has at most 64 characters (it is stored with the data)",
        "questionnaires[0].items[1].id": "an id has at most 64 characters (it is stored with the data)"}
    assert load_study(write(tmp_path, BASE.replace("id: t\n", f"id: {'s' * 64}\n"))).id == "s" * 64
