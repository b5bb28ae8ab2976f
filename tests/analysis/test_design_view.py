"""Condition ids of a study with a view factor (``robot@kitchen@view``) still name their robot and kitchen."""

from __future__ import annotations

from analysis.design import Design


def test_condition_ids_with_a_view_name_their_robot_and_kitchen() -> None:
    design = Design.from_config({"robots": ["fov_aware"], "kitchens": [{"name": "none_3"}], "factors": ["view"],
                                 "views": ["top_down", "first_person"]})
    assert design.condition_of("fov_aware@none_3@first_person") == ("fov_aware", "none_3")
    assert design.condition_of("fov_aware@none_3") == ("fov_aware", "none_3")
    assert design.condition_of("no-separator") is None
