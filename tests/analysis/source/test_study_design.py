"""The design a stored study declares (analysis.source.study_design), including the fields other parts add to the study
model: ``views`` (the view factor), ``type`` / ``reverse`` items and ``scales``."""

from __future__ import annotations

from pathlib import Path

import yaml

from analysis.source.study_design import RatingItem, ScaleSpec, StudyDesign

REPO = Path(__file__).resolve().parents[3]


def test_demo_study_has_one_factor_in_the_study_order() -> None:
    config = yaml.safe_load((REPO / "study_config" / "demo.yaml").read_text())
    design = StudyDesign.from_config(config)
    assert design.factors == ("robot",)
    assert design.levels == {"robot": ("fov_aware", "baseline")}
    assert design.horizon == 150
    assert [i.column for i in design.items] == ["quick.fluency", "quick.awareness"]


def test_kitchens_as_mappings_views_and_single_level_factors() -> None:
    config = {"robots": ["fov_aware", "baseline", "stay"], "kitchens": [{"name": "none_3"}, {"name": "mid_2"}],
              "views": ["top_down", "first_person"], "factors": ["view", "robot", "kitchen"]}
    design = StudyDesign.from_config(config)
    assert design.factors == ("view", "robot", "kitchen")
    assert design.levels["kitchen"] == ("none_3", "mid_2") and design.levels["robot"][-1] == "stay"
    one = StudyDesign.from_config({"robots": ["a", "b"], "kitchens": ["k"], "view": "first_person",
                                   "factors": ["robot", "kitchen", "view"]})
    assert one.factors == ("robot",) and one.single_level == ("kitchen", "view")
    assert StudyDesign.from_config({"robots": ["a", "b"], "kitchens": ["k1", "k2"]}).factors == ("robot", "kitchen")


def test_rating_items_reverse_and_scales_but_not_choice_text_or_end_of_study() -> None:
    config = {"robots": ["a", "b"], "kitchens": ["k"], "factors": ["robot"], "questionnaires": [
        {"id": "post", "items": [
            {"id": "fluent", "text": "t", "scale": {"min": 1, "max": 7}},
            {"id": "clumsy", "text": "t", "scale": {"min": 1, "max": 7}, "reverse": True},
            {"id": "which", "type": "choice", "text": "t", "options": ["x", "y"]},
            {"id": "comment", "type": "text", "text": "t"}],
         "scales": [{"id": "fluency", "title": "Fluency", "items": ["fluent", "clumsy"]},
                    {"id": "fluent", "items": ["fluent"]}]},
        {"id": "end", "when": "end_of_study", "items": [{"id": "age", "text": "t", "scale": {"min": 1, "max": 6}}]},
    ]}
    design = StudyDesign.from_config(config)
    assert design.items == (RatingItem("post.fluent", 1, 7), RatingItem("post.clumsy", 1, 7, reverse=True))
    assert design.scales == (ScaleSpec("post.fluency", "Fluency", ("post.fluent", "post.clumsy")),
                             ScaleSpec("post.fluent_scale", "fluent", ("post.fluent",)))
    assert design.rating_columns == ("post.fluent", "post.clumsy", "post.fluency", "post.fluent_scale")
