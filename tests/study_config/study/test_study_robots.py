"""A study's own robots (``study_config/study/robots.py``): a planner with some settings changed is a level of the
robot factor, and every mistake in one is named by field and reason."""

from __future__ import annotations

from pathlib import Path

from planner.robot_api import Person
from planner.robot_catalog import usable_names
from study_config.catalog import load_one
from study_config.study import load_study, validate_study_file
from study_config.study.warnings import study_warnings

BASE = "id: t\ntitle: Variants\nkitchens: [none_3]\nfactors: [robot]\n"
VARIANTS = """\
robots: [fov_aware, showing_no_walk, baseline]
robot_variants:
  showing_no_walk:
    planner: fov_aware_showing
    settings: {shown_value: 0, walk_price: 0, view_detour: 2}
world: {kb_delay: 2, fov_angle: 90}
"""


def write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "study.yaml"
    path.write_text(BASE + text, encoding="utf-8")
    return path


def test_a_variant_is_a_robot_level_played_by_its_planner_with_its_settings(tmp_path):
    loaded = load_one(write(tmp_path, VARIANTS))
    study = loaded.study
    assert [c.id for c in study.conditions] == ["fov_aware@none_3", "showing_no_walk@none_3", "baseline@none_3"]
    assert [loaded.planner(r) for r in study.robots] == ["fov_aware", "fov_aware_showing", "baseline"]
    variant = loaded.robot_setup("showing_no_walk", 90.0)
    plain = loaded.robot_setup("fov_aware", 90.0)
    assert dict(variant.settings) == {"shown_value": 0.0, "walk_price": 0.0, "view_detour": 2}
    assert plain.settings == (), "other robots keep their defaults"
    # The robot's model of the person is the trial's, for a variant too.
    assert variant.person == plain.person == Person(fov_angle=90.0, kb_delay=2)
    assert "unused_variant" not in {w.code for w in study_warnings(study)}


def test_every_mistake_in_a_variant_is_named_by_its_field(tmp_path):
    text = """\
robots: [fov_aware, careful, careles]
robot_variants:
  careful:
    planner: fov_aware
    settings: {shown_value: true, view_detour: -2, human_angle: 90, walk_pric: 0.1}
  baseline: {planner: baseline}
  other: {planner: nobody}
  a_variant_with_a_name_too_long_to_store: {planner: baseline}
"""
    found = {p.path: p.reason for p in validate_study_file(write(tmp_path, text))}
    installed = ", ".join(usable_names())
    assert found == {
        "robot_variants.careful.settings.shown_value": "must be a number, not True",
        "robot_variants.careful.settings.view_detour": "must be 0 or more",
        "robot_variants.careful.settings.human_angle":
            "set by the study for every robot (world.fov_angle or fov_angles), not by a robot variant",
        "robot_variants.careful.settings.walk_pric": found["robot_variants.careful.settings.walk_pric"],
        "robot_variants.baseline": "key: 'baseline' is an installed robot's name; give the variant its own name",
        "robot_variants.a_variant_with_a_name_too_long_to_store":
            "key: at most 32 characters (the name is stored with every trial)",
        "robot_variants.other.planner": f"unknown robot 'nobody'; choose one of: {installed}",
        "robots[2]": f"unknown robot 'careles'; choose one of: {installed}, careful, other, "
                     "a_variant_with_a_name_too_long_to_store",
    }
    assert installed.startswith("fov_aware, fov_aware_showing, baseline, no_rollout, stay"), \
        "the shipped robots, then any plug-ins"
    assert found["robot_variants.careful.settings.walk_pric"].startswith(
        "unknown setting 'walk_pric' of robot 'fov_aware'; its settings: ")
    assert "walk_price" in found["robot_variants.careful.settings.walk_pric"]

def test_a_variant_no_robot_plays_is_warned_about_and_a_study_without_variants_keeps_its_hash(tmp_path):
    unused = load_study(write(tmp_path, "robots: [stay]\nrobot_variants: {spare: {planner: baseline}}\n"))
    assert [w.path for w in study_warnings(unused) if w.code == "unused_variant"] == ["robot_variants.spare"]
    plain = load_study(write(tmp_path, "robots: [stay]\n"))
    assert "robot_variants" not in plain.canonical_json()
    assert plain.config_hash() == load_study(write(tmp_path, "robots: [stay]\nrobot_variants: {}\n")).config_hash()
