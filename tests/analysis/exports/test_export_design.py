"""Condition ids of a study with a view factor (``robot@kitchen@view``) still name their robot and kitchen; with view
and field-of-view factors the analysis reads the cells the server crosses."""

from __future__ import annotations

from pathlib import Path

from analysis.exports.export_design import ExportDesign


def test_condition_ids_with_a_view_name_their_robot_and_kitchen() -> None:
    design = ExportDesign.from_config({"robots": ["fov_aware"], "kitchens": [{"name": "none_3"}], "factors": ["view"],
                                 "views": ["top_down", "first_person"]})
    assert design.condition_of("fov_aware@none_3@first_person") == ("fov_aware", "none_3")
    assert design.condition_of("fov_aware@none_3") == ("fov_aware", "none_3")
    assert design.condition_of("no-separator") is None


def test_a_view_factor_makes_every_robot_kitchen_view_cell_a_condition() -> None:
    design = ExportDesign.from_config({"robots": ["fov_aware", "baseline"], "kitchens": ["none_3"],
                                 "factors": ["robot", "kitchen", "view"], "views": ["top_down", "first_person"]})
    assert design.conditions == (("fov_aware", "none_3", "top_down"), ("fov_aware", "none_3", "first_person"),
                                 ("baseline", "none_3", "top_down"), ("baseline", "none_3", "first_person"))
    assert design.cell_of("baseline", "none_3", "first_person") in design.conditions


def test_without_a_view_factor_the_cells_are_robot_by_kitchen_in_study_order() -> None:
    design = ExportDesign.from_config({"robots": ["fov_aware", "baseline"], "kitchens": ["none_3", "mid_2"],
                                 "factors": ["kitchen", "robot"]})
    assert design.conditions == (("fov_aware", "none_3"), ("baseline", "none_3"),
                                 ("fov_aware", "mid_2"), ("baseline", "mid_2"))
    assert design.cell_of("baseline", "mid_2", "first_person") == ("baseline", "mid_2")


def test_the_analysis_reads_the_same_cells_as_the_server_crosses_with_view_and_angle_factors(tmp_path: Path) -> None:
    """A stored study's configuration gives the analysis the server's conditions, the angle spelt as in the
    ids (``90``), whether the angle is within (with a view factor) or between participants."""
    import json

    from study_config.study import load_study

    for factors in ("fov_angles: [90, 112.5]\nviews: [top_down, first_person]\nfactors: [robot, view, fov_angle]\n",
                    "fov_angles: [90, 150]\nviews: [top_down, first_person]\nbetween: [fov_angle]\n"
                    "factors: [robot, view]\n"):
        path = tmp_path / "study.yaml"
        path.write_text("id: t\ntitle: T\nkitchens: [none_3]\nrobots: [fov_aware, baseline]\n" + factors)
        study = load_study(path)
        design = ExportDesign.from_config(json.loads(study.canonical_json()))
        assert design.fields == ("robot", "kitchen", "view", "fov_angle")
        assert ["@".join(cell) for cell in design.conditions] == [c.id for c in study.conditions]
        first = study.conditions[-1]
        assert design.cell_of(first.robot, first.kitchen, first.view, first.fov_angle) == design.conditions[-1]
        order = study.condition_orders()[-1]
        expected = design.expected_cells(order)
        if study.between:
            assert {"@".join(c) for c in expected} == set(order), "a participant's own group only"
        else:
            assert expected == design.conditions
