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
