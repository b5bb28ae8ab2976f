"""``wide.sav`` (analysis.exports.spss): names SPSS cannot take are renamed and keep their export name in the label."""

from __future__ import annotations

import pandas as pd
import pyreadstat

from analysis.exports.dictionary import FLAG, INT, NUM, TEXT, Column
from analysis.exports.spss import write_sav


def test_a_name_spss_cannot_take_is_renamed_and_labelled(tmp_path) -> None:
    long = "kb_gap_robot_held_pct__" + "a_very_long_robot_name" * 2 + "__kitchen"
    wide = pd.DataFrame({"participant": ["p1", "p2"], long: [1.5, None], "complete": pd.array([1, 0], "Int64")})
    columns = [Column("participant", "text", "id"), Column(long, NUM, "a measure"), Column("complete", FLAG, "all")]
    write_sav(wide, columns, {}, tmp_path / "w.sav")
    sav, meta = pyreadstat.read_sav(str(tmp_path / "w.sav"))
    assert list(sav.columns) == ["participant", "v2", "complete"]
    assert meta.column_labels[1] == f"{long}: a measure"
    assert sav["v2"].tolist()[0] == 1.5 and pd.isna(sav["v2"].tolist()[1])
    assert meta.variable_value_labels == {"complete": {0.0: "no", 1.0: "yes"}}


def test_levels_and_formats_come_from_the_data_dictionary(tmp_path) -> None:
    config = {"questionnaires": [{"id": "q", "items": [
        {"id": "trust", "type": "rating", "scale": {"min": 1, "max": 7, "labels": {1: "none", 7: "full"}}},
        {"id": "pick", "type": "choice", "options": ["left", "right"]}]}]}
    wide = pd.DataFrame({
        "participant": ["p1", "p2", "p3"], "view": ["first_person", "top_down", None],
        "order_index": pd.array([0, 1, 2], "Int64"), "ticks__fov__k1": pd.array([120, 98, None], "Int64"),
        "kb_gap_mean__fov__k1": [0.25, 1.125, 0.5], "q.trust__fov__k1": pd.array([7, 1, 4], "Int64"),
        "q.pick": pd.array([0, 1, None], "Int64"), "robot_in_fov_pct__fov__k1": [12.5, -3.0, 100.0]})
    columns = [Column("participant", TEXT, "id"), Column("view", TEXT, "group"), Column("order_index", INT, "order"),
               Column("ticks__fov__k1", INT, "ticks"), Column("kb_gap_mean__fov__k1", NUM, "gap"),
               Column("q.trust__fov__k1", INT, "trust"), Column("q.pick", INT, "pick"),
               Column("robot_in_fov_pct__fov__k1", NUM, "in view")]
    write_sav(wide, columns, config, tmp_path / "w.sav", {"view": ["top_down", "first_person"]})
    sav, meta = pyreadstat.read_sav(str(tmp_path / "w.sav"))
    assert meta.variable_measure == {
        "participant": "nominal", "view": "nominal", "order_index": "nominal", "ticks__fov__k1": "scale",
        "kb_gap_mean__fov__k1": "scale", "q.trust__fov__k1": "ordinal", "q.pick": "nominal",
        "robot_in_fov_pct__fov__k1": "scale"}
    assert meta.original_variable_types == {
        "participant": "A2", "view": "F1.0", "order_index": "F1.0", "ticks__fov__k1": "F3.0",
        "kb_gap_mean__fov__k1": "F5.3", "q.trust__fov__k1": "F1.0", "q.pick": "F1.0",
        "robot_in_fov_pct__fov__k1": "F6.1"}
    assert sav["view"].tolist()[:2] == [2.0, 1.0] and pd.isna(sav["view"].tolist()[2]), "codes of the study's order"
    assert meta.variable_value_labels["view"] == {1.0: "top_down", 2.0: "first_person"}
    assert meta.variable_value_labels["q.trust__fov__k1"] == {1.0: "none", 7.0: "full"}
    assert meta.variable_value_labels["q.pick"] == {0.0: "left", 1.0: "right"}
