"""The power simulation of a mixed design (:mod:`analysis.power_analysis.mixed_power`): groups split as assignment
splits them, each group resampled from its own pilot participants, the mixed ANOVA's tests as ``analyze`` reads them."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from analysis.power_analysis.mixed_power import (
    GroupedData,
    group_sizes,
    grouped_data,
    mixed_measure_power,
    mixed_pvalues,
    resample,
)
from analysis.source.input_errors import AnalysisInputError
from analysis.statistics.mixed_anova import mixed_anova_table

WITHIN = ("robot",)


def pilot(rng: np.random.Generator, per_group: int = 12, shift: float = 3.0) -> GroupedData:
    """Two groups of ``per_group`` pilot participants, two within cells with no within effect; the second group
    ``shift`` higher in both cells (a between effect of ``shift`` standard deviations)."""
    person = rng.normal(0, 1, size=(2 * per_group, 1))
    values = person + rng.normal(0, 1, size=(2 * per_group, 2))
    values[per_group:] += shift
    groups = tuple([0] * per_group + [1] * per_group)
    return GroupedData("ticks", values, groups, ("top_down", "first_person"), WITHIN,
                       (("fov_aware", "baseline"),), "view")


def test_groups_are_split_as_evenly_as_assignment_splits_them():
    assert group_sizes(8, 2) == [4, 4]
    assert group_sizes(7, 2) == [4, 3]
    assert group_sizes(10, 3) == [4, 3, 3]


def test_each_group_is_resampled_from_its_own_pilot_participants():
    groups = (0, 0, 0, 1, 1, 2)
    index, slots = resample(groups, [3, 2, 4], 50, np.random.default_rng(0))
    assert index.shape == (50, 9) and slots == [0, 0, 0, 1, 1, 2, 2, 2, 2]
    drawn_groups = np.asarray(groups)[index]
    assert (drawn_groups == np.asarray(slots)[None, :]).all()


def test_without_intervals_the_table_tests_the_same():
    data = pilot(np.random.default_rng(1))
    full = mixed_anova_table(data.values, data.groups, 2, [2], WITHIN, "view")
    lean = mixed_anova_table(data.values, data.groups, 2, [2], WITHIN, "view", intervals=False)
    tested = ["effect", "df1", "df2", "F", "p", "p_read", "partial_eta2", "ges", "note"]
    pd.testing.assert_frame_equal(full[tested], lean[tested])
    assert lean["partial_eta2_ci_low"].isna().all() and full["partial_eta2_ci_low"].notna().all()


def test_a_large_between_effect_is_found_and_absent_within_effects_rarely():
    """A pilot large enough that its within effects are near the population's (none): resampled, they come out
    significant about as often as α. (A small pilot's chance effect is resampled as a real one.)"""
    data = pilot(np.random.default_rng(2), per_group=60)
    table = mixed_measure_power(data, [6, 24], 300, 0.05, np.random.default_rng(3))
    assert list(dict.fromkeys(table["test"])) == ["view", "robot", "view * robot"]
    by = table.set_index(["test", "n"])
    assert by.loc[("view", 24), "power"] > 0.95
    assert by.loc[("view", 6), "power"] < by.loc[("view", 24), "power"]
    for test in ("robot", "view * robot"):  # no such effect in the population the pilot was drawn from
        assert by.loc[(test, 24), "power"] < 0.15, (test, by.loc[(test, 24), "power"])
    assert (table["pilot_n"] == 120).all() and (table["simulations"] == 300).all()


def test_a_sample_too_small_for_its_groups_counts_as_not_significant():
    data = pilot(np.random.default_rng(4))
    table = mixed_measure_power(data, [1, 2], 20, 0.05, np.random.default_rng(5))
    assert (table.loc[table["n"] == 1, "power"] == 0).all(), "a group without a participant tests nothing"
    assert (table.loc[table["n"] == 2, "power"] == 0).all(), "one participant a group leaves no error df"


def test_the_same_seed_gives_the_same_table():
    data = pilot(np.random.default_rng(6))
    a, b = (mixed_measure_power(data, [8], 40, 0.05, np.random.default_rng(7)) for _ in range(2))
    pd.testing.assert_frame_equal(a, b)


def test_a_group_without_a_complete_pilot_participant_is_named():
    kept = pd.DataFrame({"participant": ["a", "a", "b", "b"], "view": ["top_down"] * 4,
                         "robot": ["fov_aware", "baseline"] * 2, "ticks": [1.0, 2.0, 3.0, 4.0]})
    with pytest.raises(AnalysisInputError, match="view = first_person"):
        grouped_data(kept, "ticks", WITHIN, "view", "participant", ["top_down", "first_person"])


@pytest.mark.parametrize("ss_type", [3, 2])
def test_the_vectorised_tests_equal_the_mixed_anova_on_every_resample(ss_type: int) -> None:
    """Unequal groups of a 3-group × 3 × 2 pilot resampled: each sample's F and p read equal
    ``mixed_anova_table``'s, one sample at a time (Greenhouse–Geisser and Huynh–Feldt readings both exercised;
    a sample without variance is not testable)."""
    rng = np.random.default_rng(8)
    groups = (0,) * 5 + (1,) * 4 + (2,) * 6
    scale = rng.uniform(0.3, 3, size=6)
    pilot = rng.normal(size=(15, 6)) * scale + rng.normal(size=(15, 1)) + np.arange(6) * 0.4
    pilot[np.asarray(groups) == 2] += np.linspace(0, 1.5, 6)
    index, slots = resample(groups, [4, 3, 5], 60, rng)
    samples = pilot[index]
    samples[0] = 7.0
    f, p = mixed_pvalues(samples, slots, 3, [3, 2], ["robot", "kitchen"], ss_type)
    readings = set()
    for sample, f_row, p_row in zip(samples, f, p, strict=True):
        table = mixed_anova_table(sample, slots, 3, [3, 2], ["robot", "kitchen"], "view", intervals=False,
                                  ss_type=ss_type)
        readings |= set(table["correction"])
        assert f_row == pytest.approx(table["F"].to_numpy(dtype=float), rel=1e-9, nan_ok=True)
        assert p_row == pytest.approx(table["p_read"].to_numpy(dtype=float), rel=1e-9, abs=1e-14, nan_ok=True)
    assert {"GG", "HF"} <= readings, "both corrections were exercised"
    assert np.isnan(p[0]).all(), "a sample without variance is not testable"
