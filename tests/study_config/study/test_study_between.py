"""Between-participants factors in the study file: groups with their own within orders, and the designs that
cannot balance refused with the field and the reason."""

from __future__ import annotations

from pathlib import Path

import pytest

from study_config.study import load_study, validate_study_file

BASE = "id: t\ntitle: T\nkitchens: [none_3, mid_2]\nrobots: [fov_aware, baseline]\n"


def write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "study.yaml"
    path.write_text(BASE + text, encoding="utf-8")
    return path


def test_a_between_robot_gives_each_group_the_kitchens_counterbalanced(tmp_path) -> None:
    study = load_study(write(tmp_path, "between: [robot]\nfactors: [kitchen]\n"))
    assert [c.id for c in study.conditions] == ["fov_aware@none_3", "fov_aware@mid_2", "baseline@none_3",
                                                "baseline@mid_2"]
    assert study.condition_orders() == [
        ("fov_aware@none_3", "fov_aware@mid_2"), ("fov_aware@mid_2", "fov_aware@none_3"),
        ("baseline@none_3", "baseline@mid_2"), ("baseline@mid_2", "baseline@none_3")]
    assert study.order_groups() == [0, 0, 1, 1]
    assert '"between":["robot"]' in study.canonical_json()


def test_a_study_without_between_factors_keeps_its_canonical_form(tmp_path) -> None:
    study = load_study(write(tmp_path, ""))
    assert "between" not in study.canonical_json() and study.order_groups() == [0, 0, 0, 0]


@pytest.mark.parametrize(("text", "field", "reason"), [
    ("views: [top_down, first_person]\nbetween: [view]\ncounterbalancing: {scheme: fixed, order: "
     "[fov_aware@none_3@top_down]}\n", "counterbalancing.scheme", "a fixed order cannot serve the groups"),
    ("between: [fov_angle]\n", "factors", "between factor 'fov_angle' needs at least two fov_angles"),
    ("between: [robot]\n", "factors", "'robot' is both a within factor (factors) and a between factor"),
    ("robots: [fov_aware]\nbetween: [robot]\nfactors: [kitchen]\n", "factors",
     "between factor 'robot' needs at least two robots"),
])
def test_designs_that_cannot_balance_are_refused_with_field_and_reason(tmp_path, text, field, reason) -> None:
    body = text
    if text.startswith("robots:"):
        path = tmp_path / "study.yaml"
        path.write_text(BASE.replace("robots: [fov_aware, baseline]\n", "") + body, encoding="utf-8")
    else:
        path = write(tmp_path, body)
    problems = [str(p) for p in validate_study_file(path)]
    assert any(f": {field}: {reason}" in p for p in problems), problems


def test_a_between_view_group_practises_in_the_view_it_will_play(tmp_path) -> None:
    from server.flow.plan import build_plan

    study = load_study(write(tmp_path, "views: [top_down, first_person]\nbetween: [view]\n"
                                       "practice: [{kitchen: practice, robot: stay}, "
                                       "{kitchen: practice, robot: stay, view: top_down}]\n"))
    orders, groups = study.condition_orders(), study.order_groups()
    assert set(groups) == {0, 1}
    for order, group in zip(orders, groups, strict=True):
        view = ("top_down", "first_person")[group]
        trials = [s for s in build_plan(study, order) if s.kind == "trial"]
        assert {s.view for s in trials if s.trial_kind == "main"} == {view}
        # the practice round without a view of its own is in the group's view; the one that names a view keeps it
        assert [s.view for s in trials if s.trial_kind == "practice"] == [view, "top_down"]
