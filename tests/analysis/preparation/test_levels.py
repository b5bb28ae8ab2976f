"""Level order (analysis.preparation.levels): the study's order, never the alphabet."""

from __future__ import annotations

import pandas as pd
import pytest

from analysis.preparation.cells import factor_levels
from analysis.preparation.levels import apply_level_order, parse_level_option
from analysis.source.input_errors import AnalysisInputError


def test_first_appearance_by_default_and_a_given_order_otherwise() -> None:
    df = pd.DataFrame({"robot": ["fov_aware", "baseline", "fov_aware"], "kitchen": ["z", "a", "m"]})
    ordered = apply_level_order(df, ["robot", "kitchen"])
    assert factor_levels(ordered, "robot") == ["fov_aware", "baseline"]
    assert factor_levels(ordered, "kitchen") == ["z", "a", "m"]
    given = apply_level_order(df, ["kitchen"], {"kitchen": ["m", "gone", "a", "z"]})
    assert factor_levels(given, "kitchen") == ["m", "a", "z"]


def test_a_given_order_must_name_every_level_unless_lenient() -> None:
    df = pd.DataFrame({"robot": ["fov_aware", "baseline", "stay"]})
    with pytest.raises(AnalysisInputError, match=r"level\(s\) \['stay'\] that the given order"):
        apply_level_order(df, ["robot"], {"robot": ["baseline", "fov_aware"]})
    lenient = apply_level_order(df, ["robot"], {"robot": ["baseline", "fov_aware"]}, strict=False)
    assert factor_levels(lenient, "robot") == ["baseline", "fov_aware", "stay"]


def test_level_option_parsing() -> None:
    assert parse_level_option(["robot=fov_aware, baseline", "kitchen=a"]) == {
        "robot": ["fov_aware", "baseline"], "kitchen": ["a"]}
    for bad in (["robot"], ["=a,b"], ["robot=a,,b"], ["robot=a", "robot=b"], ["robot=a,a"]):
        with pytest.raises(AnalysisInputError, match="--levels"):
            parse_level_option(bad)
