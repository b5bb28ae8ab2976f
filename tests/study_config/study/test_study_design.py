"""The one design reader (study_config/study/design.py): every shipped study keeps its conditions in their order, the
server's typed study and the store's copy of it (what the analysis reads) give the same design, and a study stored
by an older version (without views, fields of view, between factors, factors, or questionnaire defaults) is still
read."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from study_config.study import Design, load_study
from study_config.study.design import ItemDesign, QuestionnaireDesign, ScaleDesign

REPO = Path(__file__).resolve().parents[3]
SHIPPED = sorted((REPO / "study_config").glob("*.yaml"))

# The condition ids of the shipped studies, as the server crossed them before the design reader existed.
SHIPPED_CONDITIONS = {
    "demo.yaml": ["fov_aware@none_3", "baseline@none_3"],
    "demo_first_person.yaml": ["fov_aware@none_3", "baseline@none_3"],
    "paper_study.yaml": ["fov_aware@none_3", "fov_aware@mid_2", "baseline@none_3", "baseline@mid_2"],
}

BASE = "id: t\ntitle: T\nkitchens: [none_3, mid_2]\nrobots: [fov_aware, baseline]\n"
VARIANTS = {
    "robot_kitchen": "",
    "kitchen_first": "factors: [kitchen, robot]\n",
    "views_within": "views: [top_down, first_person]\nfactors: [robot, view, kitchen]\n",
    "views_between": "views: [top_down, first_person]\nbetween: [view]\n",
    "angles_between": "fov_angles: [90, 112.5]\nbetween: [fov_angle]\n",
    "angles_within": "fov_angles: [150, 90]\nfactors: [fov_angle, robot, kitchen]\n",
    "robot_between": "between: [robot]\nfactors: [kitchen]\n",
    "one_view_one_angle": "view: first_person\nworld: {fov_angle: 120}\n",
    "everything": "views: [top_down, first_person]\nfov_angles: [90, 150]\nbetween: [fov_angle]\n"
                  "factors: [view, robot, kitchen]\n",
}


def stored_config(path: Path) -> dict[str, object]:
    """The study's configuration as the store keeps it (``store/studies.py``: its canonical JSON)."""
    return dict(json.loads(load_study(path).canonical_json()))


def test_every_shipped_study_is_covered() -> None:
    assert [p.name for p in SHIPPED] == sorted(SHIPPED_CONDITIONS)


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.name)
def test_a_shipped_study_keeps_its_conditions_in_their_order(path: Path) -> None:
    study = load_study(path)
    assert [c.id for c in study.conditions] == SHIPPED_CONDITIONS[path.name]
    assert [c.id for c in Design.from_config(stored_config(path)).conditions] == SHIPPED_CONDITIONS[path.name]


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.name)
def test_a_shipped_studys_stored_copy_has_the_typed_studys_whole_design(path: Path) -> None:
    study = load_study(path)
    stored = Design.from_config(stored_config(path))
    assert stored == study.design
    assert stored.horizon == study.world.horizon
    assert [q.id for q in stored.questionnaires] == [q.id for q in study.questionnaires]


def test_conditions_cross_between_then_within_factors_the_first_slowest(tmp_path: Path) -> None:
    def ids(text: str) -> list[str]:
        path = tmp_path / "study.yaml"
        path.write_text(BASE + text, encoding="utf-8")
        return [c.id for c in load_study(path).conditions]

    assert ids(VARIANTS["kitchen_first"]) == ["fov_aware@none_3", "baseline@none_3", "fov_aware@mid_2",
                                              "baseline@mid_2"]
    assert ids(VARIANTS["views_between"]) == [
        "fov_aware@none_3@top_down", "fov_aware@mid_2@top_down", "baseline@none_3@top_down", "baseline@mid_2@top_down",
        "fov_aware@none_3@first_person", "fov_aware@mid_2@first_person", "baseline@none_3@first_person",
        "baseline@mid_2@first_person"]
    assert ids(VARIANTS["angles_within"]) == [
        "fov_aware@none_3@150", "fov_aware@mid_2@150", "baseline@none_3@150", "baseline@mid_2@150",
        "fov_aware@none_3@90", "fov_aware@mid_2@90", "baseline@none_3@90", "baseline@mid_2@90"]


@pytest.mark.parametrize("variant", VARIANTS)
def test_the_stored_copy_gives_the_typed_studys_conditions_and_groups(tmp_path: Path, variant: str) -> None:
    path = tmp_path / f"{variant}.yaml"
    path.write_text(BASE + VARIANTS[variant], encoding="utf-8")
    study = load_study(path)
    stored = Design.from_config(stored_config(path))
    assert stored.conditions == study.conditions
    assert stored.groups() == study.design.groups()
    assert len(stored.groups()) == len(set(study.order_groups()))


def test_a_study_stored_before_views_angles_and_between_factors_is_read() -> None:
    old = {"id": "old", "robots": ["fov_aware", "baseline"], "kitchens": [{"name": "none_3"}, {"name": "mid_2"}],
           "factors": ["robot", "kitchen"], "world": {"fov_angle": 90, "horizon": 300}}
    design = Design.from_config(old)
    assert [c.id for c in design.conditions] == ["fov_aware@none_3", "fov_aware@mid_2", "baseline@none_3",
                                                 "baseline@mid_2"]
    assert {(c.view, c.fov_angle) for c in design.conditions} == {("top_down", 90.0)}
    assert design.between == () and design.groups() == [[c.id for c in design.conditions]]


def test_a_stored_study_without_factors_or_world_crosses_robot_and_kitchen() -> None:
    design = Design.from_config({"robots": ["stay"], "kitchens": ["none_3", "mid_2"]})
    assert design.factors == ("robot", "kitchen")
    assert [c.id for c in design.conditions] == ["stay@none_3", "stay@mid_2"]
    assert design.level_names("fov_angle") == ("120",)  # the paper's angle
    assert design.level_names("view") == ("top_down",)


def test_stored_questionnaires_are_read_with_their_defaults() -> None:
    design = Design.from_config({"robots": ["stay"], "kitchens": ["none_3"], "questionnaires": [
        {"id": "post", "items": [{"id": "fluent", "text": "Fluent", "scale": {"min": 1, "max": 7}},
                                 {"id": "why", "type": "text", "text": "Why?"}],
         "scales": [{"id": "flow", "items": ["fluent"]}]},
        {"id": "end", "when": "end_of_study", "items": [{"id": "age", "text": "Age", "scale": {"min": 1, "max": 6},
                                                         "reverse": True}]}]})
    assert design.questionnaires_shown("after_each_trial") == (QuestionnaireDesign(
        "post", "after_each_trial",
        (ItemDesign("fluent", "Fluent", "rating", (1, 7)), ItemDesign("why", "Why?", "text")),
        (ScaleDesign("flow", "flow", ("fluent",)),)),)
    assert [i.reverse for q in design.questionnaires_shown("end_of_study") for i in q.items] == [True]
    assert design.horizon is None
