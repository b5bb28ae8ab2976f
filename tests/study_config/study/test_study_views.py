"""The study's view: one view for every trial (``view``) or the levels of a ``view`` factor (``views``),
crossed and counterbalanced like the robot and the kitchen, and carried into every trial step."""

from __future__ import annotations

import itertools
import json
from collections import Counter
from pathlib import Path

import pytest

from server.flow.plan import build_plan
from study_config.study import load_study, validate_study_file

ROOT = Path(__file__).resolve().parents[3]
STUDY_CONFIG = ROOT / "study_config"

ROBOTS_KITCHENS = "id: t\ntitle: T\nkitchens: [none_3, mid_2]\nrobots: [fov_aware, baseline]\n"
ONE_KITCHEN = "id: t\ntitle: T\nkitchens: [none_3]\nrobots: [fov_aware, baseline]\n"
BOTH_VIEWS = "views: [top_down, first_person]\n"


def write(tmp_path: Path, text: str, name: str = "study.yaml") -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def problems(tmp_path: Path, text: str) -> dict[str, str]:
    found = validate_study_file(write(tmp_path, text))
    assert found, "the study should be invalid"
    return {p.path: p.reason for p in found}


def test_a_study_without_a_view_is_top_down_and_keeps_its_condition_ids(tmp_path: Path) -> None:
    study = load_study(write(tmp_path, ROBOTS_KITCHENS))
    assert study.view_levels == ("top_down",)
    assert [(c.id, c.view) for c in study.conditions] == [
        ("fov_aware@none_3", "top_down"), ("fov_aware@mid_2", "top_down"),
        ("baseline@none_3", "top_down"), ("baseline@mid_2", "top_down")]


def test_view_first_person_plays_every_trial_in_first_person_with_the_same_ids(tmp_path: Path) -> None:
    study = load_study(write(tmp_path, ROBOTS_KITCHENS + "view: first_person\n"))
    assert study.view_levels == ("first_person",)
    assert {c.view for c in study.conditions} == {"first_person"}
    assert [c.id for c in study.conditions] == [
        "fov_aware@none_3", "fov_aware@mid_2", "baseline@none_3", "baseline@mid_2"]


def test_view_as_a_factor_crosses_with_the_robot(tmp_path: Path) -> None:
    study = load_study(write(tmp_path, ONE_KITCHEN + BOTH_VIEWS + "factors: [robot, view]\n"))
    assert [c.id for c in study.conditions] == [
        "fov_aware@none_3@top_down", "fov_aware@none_3@first_person",
        "baseline@none_3@top_down", "baseline@none_3@first_person"]
    first_slowest = load_study(write(tmp_path, ONE_KITCHEN + BOTH_VIEWS + "factors: [view, robot]\n", "b.yaml"))
    assert [(c.view, c.robot) for c in first_slowest.conditions] == [
        ("top_down", "fov_aware"), ("top_down", "baseline"),
        ("first_person", "fov_aware"), ("first_person", "baseline")]


def test_three_factors_give_eight_conditions_in_a_balanced_latin_square(tmp_path: Path) -> None:
    study = load_study(write(tmp_path, ROBOTS_KITCHENS + BOTH_VIEWS + "factors: [robot, kitchen, view]\n"))
    ids = [c.id for c in study.conditions]
    assert len(ids) == 8 == len(set(ids))
    assert {(c.robot, c.kitchen, c.view) for c in study.conditions} == set(
        itertools.product(["fov_aware", "baseline"], ["none_3", "mid_2"], ["top_down", "first_person"]))
    orders = study.condition_orders()
    assert len(orders) == 8
    for position in range(8):
        assert Counter(order[position] for order in orders) == Counter(ids)
    follows = Counter(pair for order in orders for pair in itertools.pairwise(order))
    assert follows == Counter({(a, b): 1 for a in ids for b in ids if a != b})


def test_a_fixed_order_names_the_view_in_the_condition_ids(tmp_path: Path) -> None:
    order = ["baseline@none_3@first_person", "fov_aware@none_3@top_down",
             "fov_aware@none_3@first_person", "baseline@none_3@top_down"]
    text = ONE_KITCHEN + BOTH_VIEWS + "factors: [robot, view]\n" \
        f"counterbalancing: {{scheme: fixed, order: [{', '.join(order)}]}}\n"
    assert load_study(write(tmp_path, text)).condition_orders() == [tuple(order)]
    found = problems(tmp_path, text.replace("baseline@none_3@first_person", "baseline@none_3"))
    assert "unknown condition 'baseline@none_3'" in found["counterbalancing.order[0]"]


@pytest.mark.parametrize(("text", "path", "reason"), [
    (ROBOTS_KITCHENS + BOTH_VIEWS, "factors", "views has 2 entries but 'view' is not a factor"),
    (ROBOTS_KITCHENS + "view: vr\n", "view", "'top_down' or 'first_person' (got 'vr')"),
    (ROBOTS_KITCHENS + "views: [top_down, headset]\n", "views[1]", "'top_down' or 'first_person'"),
    (ROBOTS_KITCHENS + "views: []\n", "views", "needs at least one entry"),
    (ROBOTS_KITCHENS + "views: [first_person, first_person]\nfactors: [robot, kitchen, view]\n", "views[1]",
     "duplicate view 'first_person'"),
    (ROBOTS_KITCHENS + "view: top_down\nviews: [top_down]\n", "views", "write either view"),
    (ROBOTS_KITCHENS + "factors: [robot, kitchen, camera]\n", "factors[2]",
     "'robot', 'kitchen', 'view' or 'fov_angle'"),
    (ROBOTS_KITCHENS + "practice: [{kitchen: practice, robot: stay, view: 3d}]\n", "practice[0].view",
     "'top_down' or 'first_person'"),
])
def test_a_bad_view_names_the_field(tmp_path: Path, text: str, path: str, reason: str) -> None:
    found = problems(tmp_path, text)
    assert path in found, found
    assert reason in found[path]


def test_the_stored_study_always_lists_its_views(tmp_path: Path) -> None:
    plain = load_study(write(tmp_path, ROBOTS_KITCHENS, "a.yaml"))
    said = load_study(write(tmp_path, ROBOTS_KITCHENS + "view: top_down\n", "b.yaml"))
    first = load_study(write(tmp_path, ROBOTS_KITCHENS + "view: first_person\n", "c.yaml"))
    listed = load_study(write(tmp_path, ROBOTS_KITCHENS + "views: [first_person]\n", "d.yaml"))
    assert json.loads(plain.canonical_json())["views"] == ["top_down"]
    assert "view" not in json.loads(plain.canonical_json())
    assert said.config_hash() == plain.config_hash()
    assert json.loads(first.canonical_json())["views"] == ["first_person"]
    assert first.config_hash() == listed.config_hash() != plain.config_hash()


def test_every_trial_step_carries_its_view(tmp_path: Path) -> None:
    text = ONE_KITCHEN + BOTH_VIEWS + "factors: [view, robot]\n" \
        "practice: [{kitchen: practice, robot: stay}, {kitchen: practice, robot: stay, view: first_person}]\n"
    study = load_study(write(tmp_path, text))
    order = study.condition_orders()[1]
    trials = [s for s in build_plan(study, order) if s.kind == "trial"]
    assert [(s.trial_kind, s.view) for s in trials[:2]] == [("practice", "top_down"), ("practice", "first_person")]
    assert [s.condition for s in trials[2:]] == list(order)
    conditions = {c.id: c for c in study.conditions}
    assert [s.view for s in trials[2:]] == [conditions[cid].view for cid in order]


def test_practice_follows_the_study_view_by_default(tmp_path: Path) -> None:
    text = ROBOTS_KITCHENS + "view: first_person\npractice: [{kitchen: practice, robot: stay}]\n"
    study = load_study(write(tmp_path, text))
    steps = [s for s in build_plan(study, study.condition_orders()[0]) if s.kind == "trial"]
    assert {s.view for s in steps} == {"first_person"}


def test_the_first_person_demo_is_the_demo_seen_in_first_person() -> None:
    demo = load_study(STUDY_CONFIG / "demo.yaml")
    twin = load_study(STUDY_CONFIG / "demo_first_person.yaml")
    assert validate_study_file(STUDY_CONFIG / "demo_first_person.yaml") == []
    assert twin.view_levels == ("first_person",) and demo.view_levels == ("top_down",)
    assert [c.id for c in twin.conditions] == [c.id for c in demo.conditions]
    assert (twin.world, twin.timing, twin.counterbalancing, twin.questionnaires, twin.kitchens) == (
        demo.world, demo.timing, demo.counterbalancing, demo.questionnaires, demo.kitchens)
