"""Rows left out by rule (analysis.preparation.exclusions): invalid robot trials, and room for more rules."""

from __future__ import annotations

import pandas as pd

from analysis.preparation.cells import complete_cases
from analysis.preparation.exclusions import EXCLUSION_COLUMNS, ExclusionRule, apply_exclusions, missing_reasons


def cells() -> pd.DataFrame:
    rows = [{"participant": p, "robot": r, "ticks": 10.0 + i, "invalid_reason": None, "missed_decisions_pct": 0.0}
            for i, (p, r) in enumerate((p, r) for p in ("P1", "P2", "P3") for r in ("fov_aware", "baseline"))]
    df = pd.DataFrame(rows)
    df.loc[3, ["invalid_reason", "missed_decisions_pct"]] = ["missed 12% of robot decisions (threshold 5%)", 12.0]
    return df


def test_invalid_trials_are_left_out_and_listed_with_their_reason() -> None:
    kept, listed = apply_exclusions(cells(), ["robot"], "participant")
    assert len(kept) == 5 and "P2" in set(kept["participant"])
    assert list(listed.columns) == EXCLUSION_COLUMNS
    assert listed.iloc[0].to_dict() == {
        "subject": "P2", "cell": "robot=baseline", "rule": "invalid", "included": 0,
        "reason": "invalid robot trial: missed 12% of robot decisions (threshold 5%) (missed_decisions_pct = 12.0)"}
    _, excluded = complete_cases(kept, "ticks", ["robot"], "participant", missing_reasons(listed))
    assert excluded.iloc[0]["reason"].startswith("missing cell robot=baseline (excluded: invalid robot trial:")


def test_kept_on_request_still_listed_and_a_table_without_the_column_excludes_nothing() -> None:
    kept, listed = apply_exclusions(cells(), ["robot"], "participant", include={"invalid"})
    assert len(kept) == 6 and listed["included"].tolist() == [1]
    plain = cells().drop(columns=["invalid_reason"])
    kept, listed = apply_exclusions(plain, ["robot"], "participant")
    assert len(kept) == 6 and listed.empty


def test_another_rule_is_one_more_entry() -> None:
    pilot = ExclusionRule("pilot", "pilot", "--include-pilot", "simulated pilot participant")
    df = cells().assign(pilot=[1, 1, 0, 0, 0, 0])
    kept, listed = apply_exclusions(df, ["robot"], "participant", rules=(pilot,))
    assert set(kept["participant"]) == {"P2", "P3"}
    assert listed["reason"].tolist() == ["simulated pilot participant"] * 2
