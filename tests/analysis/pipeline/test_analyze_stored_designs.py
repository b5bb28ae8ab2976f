"""``steakhouse analyze --study`` on studies stored through the server's own store and flow functions (SQLite and
PostgreSQL): a measure that does not vary no longer stops the analysis (the old ``KeyError: 'F'``), a
one-factor study with three robots is analysed in the study's order with sphericity and pairwise comparisons, a
robot × kitchen × view study gets its three-factor ANOVA, a study with the view (or the field of view's angle)
between participants gets the mixed ANOVA, and the report opens with data quality."""

from __future__ import annotations

import pandas as pd
import pytest
from steakhouse_store_study import Participant, join, play_participant, study_overrides
from steakhouse_testing import write_study

from analysis.pipeline.analyze_study import attach_trial_columns
from server.cli import main
from store.engine import Store
from store.studies import sync_study
from study_config.catalog import load_one

THREE_ROBOTS = ("stay", "baseline", "fov_aware")


@pytest.fixture(scope="module")
def stored(module_db_url, tmp_path_factory):
    """A 2 × 2 study whose three participants never interrupt (``interrupts`` is 0 everywhere), a one-factor
    study of three robots in one kitchen with four participants, and a 2 × 2 × 2 robot × kitchen × view study with
    three."""
    store = Store(module_db_url)
    store.migrate()
    folder = tmp_path_factory.mktemp("studies")
    studies = {
        "quiet": load_one(write_study(folder, "quiet", **study_overrides())),
        "robots3": load_one(write_study(folder, "robots3", **study_overrides(
            robots=list(THREE_ROBOTS), kitchens=["none_3"], factors=["robot"], practice=[]))),
        "views": load_one(write_study(folder, "views", **study_overrides(
            views=["top_down", "first_person"], factors=["robot", "kitchen", "view"], practice=[]))),
        "groups": load_one(write_study(folder, "groups", **study_overrides(
            views=["top_down", "first_person"], between=["view"], factors=["robot", "kitchen"], practice=[]))),
        "angles": load_one(write_study(folder, "angles", **study_overrides(
            fov_angles=[90, 150], between=["fov_angle"], factors=["robot", "kitchen"]))),
    }
    for loaded in studies.values():
        with store.transaction() as session:
            sync_study(session, loaded.study)
    for n in range(3):
        play_participant(store, studies["quiet"], join(store, studies["quiet"], f"q{n}"),
                         Participant(seed=n, interrupt_rate=0.0))
    for n in range(4):
        play_participant(store, studies["robots3"], join(store, studies["robots3"], f"r{n}"),
                         Participant(seed=10 + n, interrupt_rate=0.05))
    for n in range(3):
        play_participant(store, studies["views"], join(store, studies["views"], f"v{n}"),
                         Participant(seed=20 + n, interrupt_rate=0.05))
    for n in range(6):
        play_participant(store, studies["groups"], join(store, studies["groups"], f"g{n}"),
                         Participant(seed=30 + n, interrupt_rate=0.05))
    for n in range(6):
        play_participant(store, studies["angles"], join(store, studies["angles"], f"a{n}"),
                         Participant(seed=40 + n, interrupt_rate=0.05))
    store.dispose()
    return module_db_url


def analyze(url: str, study: str, out, *extra: str) -> int:
    return main(["analyze", "--study", study, "--out", str(out), "--database-url", url, "--no-plots", *extra])


def test_a_measure_without_variance_is_not_testable_and_the_rest_runs(stored, tmp_path, capsys) -> None:
    assert analyze(stored, "quiet", tmp_path) == 0
    captured = capsys.readouterr()
    assert "warning: interrupts: not testable: every value is 0, nothing varies" in captured.err
    anova = pd.read_csv(tmp_path / "anova.csv")
    assert set(anova["measure"]) == {"kb_diff_freq", "kb_diff_avg", "kb_gap_mean", "kb_gap_ticks_pct", "interrupts",
                                     "interrupts_per_selection", "ticks", "robot_in_fov_pct"}
    assert (anova.groupby("measure").size() == 3).all()
    flat = anova[anova["measure"] == "interrupts"]
    assert set(flat["note"]) == {"not testable: every value is 0, nothing varies"} and flat["F"].isna().all()
    report = (tmp_path / "report.md").read_text()
    assert report.index("## Data quality") < report.index("## Method") < report.index("## kb_diff_freq")
    assert report.index("## kb_diff_avg") < report.index("## kb_gap_mean")  # the paper's gap first, ours after
    assert "Study quiet: 3 participants in the store" in report
    assert "- interrupts: not testable: every value is 0, nothing varies" in report
    descriptives = pd.read_csv(tmp_path / "descriptives.csv")
    assert descriptives["robot"].drop_duplicates().tolist() == ["stay", "baseline"]  # the study's order
    assert descriptives["kitchen"].drop_duplicates().tolist() == ["none_3", "mid_2"]


def test_one_factor_of_three_robots_in_the_study_order(stored, tmp_path) -> None:
    assert analyze(stored, "robots3", tmp_path, "--dv", "ticks,robot_in_fov_pct,q.a") == 0
    anova = pd.read_csv(tmp_path / "anova.csv")
    assert anova["effect"].unique().tolist() == ["robot"]
    # Greenhouse-Geisser's epsilon lies in [1/(k-1), 1]; at the lower bound it comes out of floating point a hair off.
    assert (anova["df1"] == 2).all() and anova["eps_gg"].between(0.5 - 1e-9, 1 + 1e-9).all()
    assert set(anova["correction"]) <= {"GG", "HF"}
    pairwise = pd.read_csv(tmp_path / "pairwise.csv")
    assert list(zip(pairwise["level_1"], pairwise["level_2"], strict=True))[:3] == [
        ("stay", "baseline"), ("stay", "fov_aware"), ("baseline", "fov_aware")]
    ranks = pd.read_csv(tmp_path / "rank_tests.csv")
    assert ranks["measure"].unique().tolist() == ["q.a"] and ranks["test"].tolist() == ["Friedman"]
    assert pd.read_csv(tmp_path / "simple_effects.csv").empty
    report = (tmp_path / "report.md").read_text()
    assert "Within factors: robot." in report and "Plots" not in report  # --no-plots
    assert "### Order and carry-over" in report and "### Sphericity (Mauchly's test)" in report


def test_robot_kitchen_view_gets_the_three_factor_analysis(stored, tmp_path) -> None:
    assert analyze(stored, "views", tmp_path, "--dv", "ticks,robot_in_fov_pct") == 0
    anova = pd.read_csv(tmp_path / "anova.csv").query("measure == 'ticks'")
    assert anova["effect"].tolist() == ["robot", "kitchen", "view", "robot * kitchen", "robot * view",
                                        "kitchen * view", "robot * kitchen * view"]
    assert (anova["df2"] == 2).all()
    simple = pd.read_csv(tmp_path / "simple_effects.csv").query("measure == 'ticks'")
    assert simple.groupby("factor", sort=False).size().to_dict() == {"robot": 4, "kitchen": 4, "view": 4}
    descriptives = pd.read_csv(tmp_path / "descriptives.csv")
    assert descriptives["view"].drop_duplicates().tolist() == ["top_down", "first_person"]
    assert "Within factors: robot, kitchen, view." in (tmp_path / "report.md").read_text()


def test_the_export_of_a_view_study_has_a_wide_column_per_view_and_counts_every_view_for_completeness(
        stored, tmp_path) -> None:
    assert main(["export", "--study", "views", "--out", str(tmp_path), "--database-url", stored]) == 0
    wide = pd.read_csv(tmp_path / "wide.csv")
    ticks = [c for c in wide.columns if c.startswith("ticks__")]
    assert len(ticks) == 8 and {c.rsplit("__", 1)[1] for c in ticks} == {"top_down", "first_person"}
    assert wide["complete"].tolist() == [1, 1, 1] and not wide[ticks].isna().any().any()


def test_cells_carry_their_trials_validity_when_the_export_records_it() -> None:
    cells = pd.DataFrame({"participant": ["a", "a"], "trial_id": [1, 2], "ticks": [10, 12]})
    trials = pd.DataFrame({"trial_id": [1, 2, 3], "invalid_reason": [None, "missed 20%", None],
                           "missed_decisions_pct": [0.0, 20.0, 1.0]})
    joined = attach_trial_columns(cells, trials)
    assert joined["invalid_reason"].tolist()[1] == "missed 20%" and joined["missed_decisions_pct"].tolist() == [0, 20]
    assert attach_trial_columns(cells, trials.drop(columns=["invalid_reason", "missed_decisions_pct"])).equals(cells)


def test_a_view_between_participants_gets_the_mixed_anova(stored, tmp_path) -> None:
    assert analyze(stored, "groups", tmp_path, "--dv", "ticks,kb_gap_mean") == 0
    cells = pd.read_csv(tmp_path / "data" / "cells.csv")
    assert (cells.groupby("participant")["view"].nunique() == 1).all(), "one view per participant"
    assert sorted(cells.drop_duplicates("participant")["view"].value_counts().tolist()) == [3, 3]
    assert (cells.groupby("participant").size() == 4).all(), "every robot × kitchen condition in each group"
    people = pd.read_csv(tmp_path / "data" / "participants.csv")
    assert (people["complete"] == 1).all(), "complete in their own group's conditions"
    assert pd.read_csv(tmp_path / "data" / "excluded.csv").empty
    wide = pd.read_csv(tmp_path / "data" / "wide.csv")
    assert (wide["complete"] == 1).all() and sorted(wide["view"]) == ["first_person"] * 3 + ["top_down"] * 3
    assert [c for c in wide.columns if c.startswith("ticks__")] == [
        "ticks__stay__none_3", "ticks__stay__mid_2", "ticks__baseline__none_3", "ticks__baseline__mid_2"], \
        "one column per within cell, whatever the group"
    # Every participant has every within cell's column, holding their own round's value: empty only where the long
    # table's cell is empty too (kb_diff_avg in a round without a gap tick, human_plating_pct in a round nobody
    # plated: the rounds' seeds are drawn at random, so either can happen), never left empty by the other group.
    long = cells.set_index(["participant", "robot", "kitchen"])
    by_participant = wide.set_index("participant")
    for column in wide.filter(like="__").columns:
        measure, robot, kitchen = column.split("__")
        own = long.xs((robot, kitchen), level=("robot", "kitchen"))[measure]
        assert set(own.index) == set(by_participant.index), f"{column}: a participant without this cell"
        pd.testing.assert_series_equal(by_participant[column], own.reindex(by_participant.index),
                                       check_names=False, check_dtype=False, obj=column)
    assert people.set_index("participant")["view"].to_dict() == wide.set_index("participant")["view"].to_dict()
    anova = pd.read_csv(tmp_path / "anova.csv")
    ticks = anova[anova["measure"] == "ticks"]
    assert ticks["effect"].tolist() == ["view", "robot", "view * robot", "kitchen", "view * kitchen",
                                        "robot * kitchen", "view * robot * kitchen"]
    assert ticks.loc[ticks["effect"] == "view", "df2"].tolist() == [4], "6 participants in 2 groups"
    assert "mixed (split-plot) ANOVA" in (tmp_path / "report.md").read_text()
    end = pd.read_csv(tmp_path / "end_of_study.csv")
    assert end.set_index("group")["n"].to_dict() == {"all participants": 6, "view=top_down": 3,
                                                     "view=first_person": 3}, "the end of study per group too"


def test_a_field_of_view_between_participants_gets_the_mixed_anova(stored, tmp_path) -> None:
    assert analyze(stored, "angles", tmp_path, "--dv", "ticks,robot_in_fov_pct") == 0
    data = tmp_path / "data"
    cells = pd.read_csv(data / "cells.csv")
    assert (cells.groupby("participant")["fov_angle"].nunique() == 1).all(), "one angle per participant"
    assert sorted(cells.drop_duplicates("participant")["fov_angle"].value_counts().tolist()) == [3, 3]
    assert set(zip(cells["condition"].str.rsplit("@", n=1).str[1].astype(int), cells["fov_angle"], strict=True)) == {
        (90, 90), (150, 150)}
    trials = pd.read_csv(data / "trials.csv")
    practice = trials[trials["kind"] == "practice"].set_index("participant")["fov_angle"]
    assert practice.to_dict() == cells.drop_duplicates("participant").set_index("participant")["fov_angle"].to_dict(), \
        "each participant practised at their group's angle"
    assert set(pd.read_csv(data / "ticks.csv")["fov_angle"]) == {90, 150}
    people = pd.read_csv(data / "participants.csv", dtype={"fov_angle": str})
    assert (people["complete"] == 1).all() and sorted(people["fov_angle"]) == ["150"] * 3 + ["90"] * 3
    wide = pd.read_csv(data / "wide.csv", dtype={"fov_angle": str})
    assert (wide["complete"] == 1).all() and "ticks__stay__none_3" in wide and "ticks__stay__none_3__90" not in wide
    groups = people.set_index("participant")["fov_angle"]
    assert wide.set_index("participant")["fov_angle"].to_dict() == groups.to_dict()
    anova = pd.read_csv(tmp_path / "anova.csv")
    ticks = anova[anova["measure"] == "ticks"]
    assert ticks["effect"].tolist() == ["fov_angle", "robot", "fov_angle * robot", "kitchen", "fov_angle * kitchen",
                                        "robot * kitchen", "fov_angle * robot * kitchen"]
    assert ticks.loc[ticks["effect"] == "fov_angle", "df2"].tolist() == [4], "6 participants in 2 groups"
    descriptives = pd.read_csv(tmp_path / "descriptives.csv", dtype={"fov_angle": str})
    assert descriptives["fov_angle"].drop_duplicates().tolist() == ["90", "150"], "the study's order"
    assert "mixed (split-plot) ANOVA" in (tmp_path / "report.md").read_text()


def test_wide_sav_opens_as_spss_needs_it_and_gives_analyzes_mixed_anova(stored, tmp_path) -> None:
    """SPSS's GLM Repeated Measures takes one variable per within cell and the group as a coded between factor:
    wide.sav read with pyreadstat, reshaped by this test alone, gives the F of every effect that analyze gives
    (the split-plot sums of squares computed the textbook way, tests/analysis/split_plot.py)."""
    import pyreadstat
    from split_plot import textbook

    assert analyze(stored, "groups", tmp_path, "--dv", "ticks,kb_gap_mean") == 0
    sav, meta = pyreadstat.read_sav(str(tmp_path / "data" / "wide.sav"))
    assert meta.variable_value_labels["view"] == {1.0: "top_down", 2.0: "first_person"}
    measure = meta.variable_measure
    assert measure["participant"] == measure["view"] == measure["complete"] == measure["order_index"] == "nominal"
    assert measure["ticks__stay__none_3"] == measure["kb_gap_mean__stay__none_3"] == "scale"
    assert measure["q.a__stay__none_3"] == measure["end.age"] == "ordinal", "ratings are ordinal"
    formats = {name: str(kind) for name, kind in meta.original_variable_types.items()}
    assert formats["ticks__stay__none_3"].endswith(".0") and formats["complete"] == "F1.0"
    assert formats["view"].endswith(".0") and formats["participant"].startswith("A")
    assert not formats["kb_gap_mean__stay__none_3"].endswith(".0"), "a mean keeps its decimals"
    anova = pd.read_csv(tmp_path / "anova.csv")
    for dv in ("ticks", "kb_gap_mean"):
        rows = [{"participant": person, "view": meta.variable_value_labels["view"][code], "robot": robot,
                 "kitchen": kitchen, dv: value}
                for person, code, *cells in sav[["participant", "view", *(f"{dv}__{r}__{k}" for r, k in CELLS)]]
                .itertuples(index=False)
                for (robot, kitchen), value in zip(CELLS, cells, strict=True)]
        expected = textbook(pd.DataFrame(rows), dv, "view", ["robot", "kitchen"], "participant")
        ours = anova[anova["measure"] == dv].set_index("effect")
        for effect, (ss, error, df1, df2) in expected.items():
            assert ours.loc[effect, "F"] == pytest.approx((ss / df1) / (error / df2), rel=1e-9), (dv, effect)
            assert (ours.loc[effect, "df1"], ours.loc[effect, "df2"]) == (df1, df2)


CELLS = [("stay", "none_3"), ("stay", "mid_2"), ("baseline", "none_3"), ("baseline", "mid_2")]
