"""Complete cases and input validation."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from analysis.preparation.cells import complete_cases, factor_levels, require_columns
from analysis.source.input_errors import AnalysisInputError

WITHIN = ["robot", "kitchen"]


def test_complete_table_loses_nobody(cells) -> None:
    df = cells()
    clean, excluded = complete_cases(df, "ticks", WITHIN, "participant")
    pd.testing.assert_frame_equal(clean, df)
    assert list(excluded.columns) == ["subject", "reason"]
    assert excluded.empty


def test_subject_missing_a_cell_is_excluded_with_the_cell_named(cells) -> None:
    df = cells()
    gone = (df["participant"] == "P04") & (df["robot"] == "baseline") & (df["kitchen"] == "mid_2")
    clean, excluded = complete_cases(df[~gone], "ticks", WITHIN, "participant")
    assert "P04" not in set(clean["participant"])
    assert clean["participant"].nunique() == 11
    assert excluded.to_dict("records") == [
        {"subject": "P04", "reason": "missing cell robot=baseline, kitchen=mid_2"}
    ]


def test_nan_value_excludes_only_for_that_measure(cells) -> None:
    df = cells()
    hit = (df["participant"] == "P07") & (df["robot"] == "fov_aware") & (df["kitchen"] == "none_3")
    df.loc[hit, "interrupts"] = np.nan
    _, for_interrupts = complete_cases(df, "interrupts", WITHIN, "participant")
    _, for_ticks = complete_cases(df, "ticks", WITHIN, "participant")
    assert for_interrupts.to_dict("records") == [
        {
            "subject": "P07",
            "reason": "missing value of interrupts in cell robot=fov_aware, kitchen=none_3",
        }
    ]
    assert for_ticks.empty


def test_several_problems_are_all_listed(cells) -> None:
    df = cells()
    df = df[~((df["participant"] == "P02") & (df["kitchen"] == "mid_2"))]
    _, excluded = complete_cases(df, "ticks", WITHIN, "participant")
    assert excluded.at[0, "reason"] == (
        "missing cell robot=baseline, kitchen=mid_2; missing cell robot=fov_aware, kitchen=mid_2"
    )


def test_missing_column_names_it_and_lists_the_available_ones(cells) -> None:
    with pytest.raises(AnalysisInputError) as info:
        complete_cases(cells(), "tick", WITHIN, "participant")
    message = str(info.value)
    assert "'tick'" in message
    assert "available columns: 'participant', 'robot', 'kitchen', 'ticks', 'interrupts'" in message
    with pytest.raises(AnalysisInputError, match="'pid' not found"):
        require_columns(cells(), ["robot", "pid"])


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (lambda d: d.assign(ticks="fast"), "'ticks' is the dependent variable but is not numeric"),
        (lambda d: d.assign(kitchen="mid_2"), "'kitchen' has 1 level"),
        (lambda d: pd.concat([d, d.iloc[:1]]), "P01 has more than one row in cell"),
        (lambda d: d.assign(robot=d["robot"].where(d.index != 3)), "'robot' has 1 empty value"),
    ],
)
def test_malformed_designs_are_refused(cells, change, message) -> None:
    with pytest.raises(AnalysisInputError, match=message):
        complete_cases(change(cells()), "ticks", WITHIN, "participant")


def test_factor_levels_in_order_of_first_appearance_or_category_order(cells) -> None:
    df = cells()
    assert factor_levels(df, "kitchen") == ["none_3", "mid_2"]
    assert factor_levels(df.iloc[::-1], "kitchen") == ["mid_2", "none_3"]
    df["kitchen"] = pd.Categorical(df["kitchen"], categories=["none_3", "mid_2", "unused"])
    assert factor_levels(df, "kitchen") == ["none_3", "mid_2"]
