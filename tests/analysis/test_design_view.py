"""Condition ids of a study with a view factor (``robot@kitchen@view``) still name their robot and kitchen."""

from __future__ import annotations

from analysis.design import Design


def test_condition_ids_with_a_view_name_their_robot_and_kitchen() -> None:
    design = Design.from_config({"robots": ["fov_aware"], "kitchens": [{"name": "none_3"}], "factors": ["view"],
                                 "views": ["top_down", "first_person"]})
    assert design.condition_of("fov_aware@none_3@first_person") == ("fov_aware", "none_3")
    assert design.condition_of("fov_aware@none_3") == ("fov_aware", "none_3")
    assert design.condition_of("no-separator") is None


def test_a_view_factor_makes_every_robot_kitchen_view_cell_a_condition() -> None:
    design = Design.from_config({"robots": ["fov_aware", "baseline"], "kitchens": ["none_3"],
                                 "factors": ["robot", "kitchen", "view"], "views": ["top_down", "first_person"]})
    assert design.conditions == (("fov_aware", "none_3", "top_down"), ("fov_aware", "none_3", "first_person"),
                                 ("baseline", "none_3", "top_down"), ("baseline", "none_3", "first_person"))
    assert design.cell_of("baseline", "none_3", "first_person") in design.conditions


def test_without_a_view_factor_the_cells_are_robot_by_kitchen_in_study_order() -> None:
    design = Design.from_config({"robots": ["fov_aware", "baseline"], "kitchens": ["none_3", "mid_2"],
                                 "factors": ["kitchen", "robot"]})
    assert design.conditions == (("fov_aware", "none_3"), ("baseline", "none_3"),
                                 ("fov_aware", "mid_2"), ("baseline", "mid_2"))
    assert design.cell_of("baseline", "mid_2", "first_person") == ("baseline", "mid_2")
