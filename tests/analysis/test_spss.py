"""``wide.sav`` (analysis.spss): names SPSS cannot take are renamed and keep their export name in the label."""

from __future__ import annotations

import pandas as pd
import pyreadstat

from analysis.dictionary import FLAG, NUM, Column
from analysis.spss import write_sav


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
