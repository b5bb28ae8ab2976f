"""The field of view as a study factor: ``fov_angles`` are the levels of ``fov_angle``, between participants (each
group plays, and practises, at its angle) or within like ``view``; a study without them keeps its one
``world.fov_angle`` and its config hash; impossible designs are refused with the field and the reason."""

from __future__ import annotations

from pathlib import Path

import pytest

from server.cli import main
from server.flow.plan import build_plan
from study_config.study import load_study, validate_study_file

BASE = "id: t\ntitle: T\nkitchens: [none_3, mid_2]\nrobots: [fov_aware, baseline]\n"


def write(tmp_path: Path, text: str, base: str = BASE) -> Path:
    path = tmp_path / "study.yaml"
    path.write_text(base + text, encoding="utf-8")
    return path


def test_a_between_angle_gives_each_group_its_conditions_at_its_angle(tmp_path) -> None:
    study = load_study(write(tmp_path, "fov_angles: [90, 120, 150]\nbetween: [fov_angle]\n"
                                       "practice: [{kitchen: practice, robot: stay}]\n"))
    assert study.fov_angle_levels == (90.0, 120.0, 150.0)
    assert [c.id for c in study.conditions][:4] == ["fov_aware@none_3@90", "fov_aware@mid_2@90",
                                                    "baseline@none_3@90", "baseline@mid_2@90"]
    assert [c.fov_angle for c in study.conditions] == [90.0] * 4 + [120.0] * 4 + [150.0] * 4
    orders, groups = study.condition_orders(), study.order_groups()
    assert groups == [0] * 4 + [1] * 4 + [2] * 4
    for order, group in zip(orders, groups, strict=True):
        assert {cid.rsplit("@", 1)[1] for cid in order} == {("90", "120", "150")[group]}
        plan = build_plan(study, order)
        trials = [s for s in plan if s.kind == "trial"]
        assert [s.fov_angle for s in trials] == [(90.0, 120.0, 150.0)[group]] * 5, "practice at the group's angle"
    assert '"fov_angles":[90.0,120.0,150.0]' in study.canonical_json()


def test_a_within_angle_is_crossed_and_counterbalanced_like_a_view(tmp_path) -> None:
    study = load_study(write(tmp_path, "kitchens: [none_3]\nfov_angles: [90, 112.5]\nfactors: [robot, fov_angle]\n",
                             "id: t\ntitle: T\nrobots: [fov_aware, baseline]\n"))
    assert [c.id for c in study.conditions] == ["fov_aware@none_3@90", "fov_aware@none_3@112.5",
                                                "baseline@none_3@90", "baseline@none_3@112.5"]
    assert len(study.condition_orders()) == 4 and set(study.order_groups()) == {0}
    trials = [s for s in build_plan(study, study.condition_orders()[1]) if s.kind == "trial"]
    conditions = [s.condition for s in trials if s.condition is not None]
    assert len(conditions) == len(trials), "every trial names its condition"
    assert [s.fov_angle for s in trials] == [112.5 if c.endswith("112.5") else 90.0 for c in conditions]


def test_a_study_without_angles_keeps_its_world_angle_ids_and_hash(tmp_path) -> None:
    study = load_study(write(tmp_path, "world: {fov_angle: 100}\n"))
    assert study.fov_angle_levels == (100.0,) and "fov_angles" not in study.canonical_json()
    assert next(c.id for c in study.conditions) == "fov_aware@none_3"
    assert {c.fov_angle for c in study.conditions} == {100.0}
    assert study.trial_angle(None) == 100.0 and study.trial_angle(150.0) == 150.0


def test_validate_names_the_groups_and_the_angles(tmp_path, capsys) -> None:
    assert main(["study", "validate", str(write(tmp_path, "fov_angles: [90, 150]\nbetween: [fov_angle]\n"))]) == 0
    out = capsys.readouterr().out
    assert "8 condition orders (latin_square, in 2 groups of fov_angle between participants)" in out
    assert "field of view 90° / 150°" in out


@pytest.mark.parametrize(("text", "field", "reason"), [
    ("fov_angles: [0, 90]\nbetween: [fov_angle]\n", "fov_angles[0]", "should be greater than 0"),
    ("fov_angles: [90, 400]\nbetween: [fov_angle]\n", "fov_angles[1]", "should be less than or equal to 360"),
    ("fov_angles: [90, 90.0]\nbetween: [fov_angle]\n", "fov_angles[1]", "duplicate field-of-view angle '90'"),
    ("fov_angles: []\nbetween: [fov_angle]\n", "fov_angles", ""),
    ("fov_angles: [90, 150]\n", "factors", "fov_angles has 2 entries but 'fov_angle' is not a factor"),
    ("between: [fov_angle]\n", "factors", "between factor 'fov_angle' needs at least two fov_angles"),
    ("fov_angles: [90]\nbetween: [fov_angle]\n", "factors", "between factor 'fov_angle' needs at least two"),
    ("fov_angles: [90, 150]\nbetween: [fov_angle]\nfactors: [robot, kitchen, fov_angle]\n", "factors",
     "'fov_angle' is both a within factor (factors) and a between factor"),
    ("fov_angles: [90, 150]\nbetween: [fov_angle]\nworld: {fov_angle: 120}\n", "world.fov_angle",
     "write either world.fov_angle (one field of view for every trial) or fov_angles"),
    ("fov_angles: [90, 150]\nbetween: [fov_angle]\ncounterbalancing: {scheme: fixed, order: [fov_aware@none_3@90]}\n",
     "counterbalancing.scheme", "a fixed order cannot serve the groups"),
])
def test_impossible_angle_designs_are_refused_with_field_and_reason(tmp_path, text, field, reason) -> None:
    problems = [str(p) for p in validate_study_file(write(tmp_path, text))]
    assert any(f": {field}: {reason}" in p for p in problems), problems
