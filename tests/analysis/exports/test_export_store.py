"""``steakhouse export`` of a study stored through the server's own store and flow functions, on SQLite and
PostgreSQL: every file and column documented, flagged and incomplete participants listed with reasons (never
dropped), practice flagged, and the cell measures equal to a recomputation from ticks.csv."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest
from steakhouse_store_study import Participant, abandon_current_trial, join, play_participant, study_overrides
from steakhouse_testing import write_study

from analysis.exports.dataset import FILES
from analysis.exports.dictionary import wide_column
from analysis.measures.trial_measures import TRIAL_MEASURES
from server.cli import main
from server.flow import service
from server.flow.progress import Move
from store import participants
from store.engine import Store
from store.studies import sync_study
from store.tables import ParticipantRow
from study_config.catalog import load_one

CONDITIONS = {("stay", "none_3"), ("stay", "mid_2"), ("baseline", "none_3"), ("baseline", "mid_2")}


@pytest.fixture(scope="module")
def stored(module_db_url, tmp_path_factory):
    """Four complete participants, one excluded by the experimenter, one test run, one whose last main trial
    was abandoned, one who declined consent (played once per database for the whole module)."""
    store = Store(module_db_url)
    store.migrate()
    loaded_2x2 = load_one(write_study(tmp_path_factory.mktemp("studies"), "two_by_two", **study_overrides()))
    with store.transaction() as session:
        sync_study(session, loaded_2x2.study)
    ids = {}
    for n in range(4):
        ids[f"full{n}"] = join(store, loaded_2x2, f"full{n}")
        play_participant(store, loaded_2x2, ids[f"full{n}"], Participant(seed=n, interrupt_rate=0.03 * (n + 1)))
    ids["excluded"] = join(store, loaded_2x2, "excluded")
    play_participant(store, loaded_2x2, ids["excluded"], Participant(seed=11))
    ids["test"] = join(store, loaded_2x2, "test", test_run=True)
    ids["partial"] = join(store, loaded_2x2, "partial")
    play_participant(store, loaded_2x2, ids["partial"], Participant(seed=12), main_trials=3)
    abandon_current_trial(store, loaded_2x2, ids["partial"])
    declined = service.join(store, loaded_2x2, {"PROLIFIC_PID": "declined"}, False)
    service.move(store, declined.participant.id, Move.DECLINE_CONSENT)
    ids["declined"] = declined.participant.id
    with store.transaction() as session:
        participants.set_flags(session, ids["excluded"], test_run=None, excluded=True, reason="fell asleep")
    with store.transaction() as session:
        public = {name: session.get_one(ParticipantRow, pid).public_id for name, pid in ids.items()}
    store.dispose()
    return module_db_url, public


@pytest.fixture(scope="module")
def exported(stored, tmp_path_factory):
    url, ids = stored
    out = tmp_path_factory.mktemp("export")
    assert main(["export", "--study", "two_by_two", "--out", str(out), "--database-url", url]) == 0
    tables = {name: pd.read_csv(out / name) for name in FILES}
    return out, tables, ids


def test_the_command_says_what_it_wrote(stored, tmp_path, capsys) -> None:
    url, _ = stored
    assert main(["export", "--study", "two_by_two", "--out", str(tmp_path), "--database-url", url]) == 0
    out = capsys.readouterr().out
    assert "study two_by_two: 8 participants, 30 trial attempts, 19 cells" in out
    # 7 CSVs, wide.sav, the dictionary twice
    assert "4 participants listed in excluded.csv" in out and f"wrote 10 files to {tmp_path}" in out


def test_every_file_and_every_column_is_in_the_data_dictionary(exported) -> None:
    out, tables, _ = exported
    dictionary = pd.read_csv(out / "data_dictionary.csv")
    markdown = (out / "data_dictionary.md").read_text()
    for name, table in tables.items():
        documented = dictionary[dictionary["file"] == name]["column"].tolist()
        assert documented == list(table.columns), name
        assert f"## {name}" in markdown
    assert dictionary["description"].str.len().min() > 5
    assert {"q.a", "q.b"} <= set(tables["cells.csv"].columns)
    assert "answer to q.a: “A”" in markdown


def test_flagged_and_incomplete_participants_are_listed_with_reasons_never_dropped(exported) -> None:
    _, tables, ids = exported
    people = tables["participants.csv"].set_index("participant")
    assert set(people.index) == set(ids.values())
    assert people.loc[ids["excluded"], "excluded"] == 1
    assert people.loc[ids["excluded"], "exclusion_reason"] == "fell asleep"
    assert people.loc[ids["test"], "test_run"] == 1
    assert people.loc[ids["full0"], "complete"] == 1 and people.loc[ids["partial"], "complete"] == 0
    assert people.loc[ids["full0"], "recruit_id"] == "full0"
    excluded = tables["excluded.csv"].set_index("participant")
    assert set(excluded.index) == {ids["excluded"], ids["test"], ids["partial"], ids["declined"]}
    assert excluded.loc[ids["excluded"], "reason"] == "excluded by the experimenter: fell asleep"
    assert excluded.loc[ids["test"], ["category", "reason"]].tolist() == ["test_run", "test run"]
    partial = excluded.loc[ids["partial"]]
    assert partial["category"] == "incomplete" and partial["in_cells"] == 1
    assert partial["reason"].count("missing cell robot=") == 1
    assert partial["reason"].endswith("(main trial 4 abandoned (grace_expired))")
    assert "participant screened_out" in excluded.loc[ids["declined"], "reason"]
    cells = tables["cells.csv"]
    assert set(cells["participant"]) == {ids[f"full{n}"] for n in range(4)} | {ids["partial"]}
    sizes = cells.groupby("participant").size()
    assert sizes[ids["partial"]] == 3 and (sizes.drop(ids["partial"]) == 4).all()


def test_practice_and_flagged_trials_are_exported_but_not_in_cells(exported) -> None:
    _, tables, ids = exported
    trials = tables["trials.csv"]
    practice = trials[trials["kind"] == "practice"]
    assert len(practice) == 6 and (practice["in_cells"] == 0).all()
    flagged = trials[trials["participant"] == ids["excluded"]]
    assert len(flagged) == 5 and (flagged["participant_excluded"] == 1).all() and (flagged["in_cells"] == 0).all()
    used = trials[trials["in_cells"] == 1]
    assert sorted(used["trial_id"]) == sorted(tables["cells.csv"]["trial_id"])
    assert (trials["ticks"] == trials["ticks_stored"]).all()
    assert set(tables["ticks.csv"]["trial_id"]) == set(trials[trials["ticks_stored"] > 0]["trial_id"])
    [abandoned] = trials[trials["status"] == "abandoned"].itertuples()
    assert (abandoned.participant, abandoned.end_reason, abandoned.in_cells) == (ids["partial"], "grace_expired", 0)
    assert abandoned.ticks_stored == 0 and pd.isna(abandoned.kb_gap_mean)


def test_cell_measures_equal_a_recomputation_from_ticks_csv(exported) -> None:
    _, tables, _ = exported
    cells, ticks, trials = tables["cells.csv"], tables["ticks.csv"], tables["trials.csv"]
    per_trial = ticks.groupby("trial_id").agg(
        n=("tick", "size"), last=("tick", "max"), gap=("kb_gap_total", "mean"),
        any_gap=("kb_gap_total", lambda s: 100 * (s > 0).mean()), fov=("robot_in_fov", lambda s: 100 * s.mean()),
        board=("kb_gap_board", lambda s: 100 * s.mean()), switches=("subtask_switch", "sum"),
        redundant=("redundant_action", "sum"), misses=("robot_missed", "sum"))
    merged = cells.merge(per_trial, left_on="trial_id", right_index=True)
    assert len(merged) == len(cells)
    assert (merged["ticks"] == merged["n"]).all() and (merged["n"] == merged["last"]).all()
    for measure, column in [("kb_gap_mean", "gap"), ("kb_gap_ticks_pct", "any_gap"), ("robot_in_fov_pct", "fov"),
                            ("kb_gap_board_pct", "board"), ("subtask_switches", "switches"),
                            ("redundant_actions", "redundant"), ("deadline_misses", "misses")]:
        assert merged[measure].to_numpy() == pytest.approx(merged[column].to_numpy()), measure
    assert set(zip(cells["robot"], cells["kitchen"], strict=True)) == CONDITIONS
    assert cells["interrupts_per_selection"].to_numpy() == pytest.approx(
        (100 * cells["interrupts"] / (cells["interrupts"] + cells["selections"])).to_numpy())
    assert cells["finished"].isin([0, 1]).all() and trials["score"].max() == 20
    # the robots differ: the simulated partner holds things the participant cannot always see
    stay = cells[cells["robot"] == "stay"]
    assert (stay["kb_gap_robot_held_pct"] == 0).all()
    assert cells[cells["robot"] == "baseline"]["kb_gap_robot_held_pct"].mean() > 0


def test_wide_has_one_row_per_participant_and_a_column_per_measure_and_condition(exported) -> None:
    _, tables, ids = exported
    wide, cells = tables["wide.csv"].set_index("participant"), tables["cells.csv"]
    assert set(wide.index) == set(cells["participant"])
    assert wide.loc[ids["partial"], "complete"] == 0 and wide.loc[ids["full1"], "complete"] == 1
    for row in cells.itertuples():
        for measure in (*TRIAL_MEASURES, "q.a"):
            value = wide.loc[row.participant, wide_column(measure, row.robot, row.kitchen)]
            assert value == pytest.approx(cells.loc[row.Index, measure], nan_ok=True)
    assert wide.loc[ids["full0"], "end.age"] in range(1, 7)
    assert pd.isna(wide.loc[ids["partial"], "end.age"])
    answers = tables["answers.csv"]
    first = answers[(answers["participant"] == ids["full0"]) & (answers["questionnaire"] == "q")]
    assert len(first) == 8 and first["condition"].nunique() == 4
    assert (first["condition"] == first["robot"] + "@" + first["kitchen"]).all()
    # each answer carries the view and field of view of the trial it followed, as that trial's cell does
    mine = cells[cells["participant"] == ids["full0"]].set_index("condition")
    for column in ("view", "fov_angle"):
        assert (first[column] == first["condition"].map(mine[column])).all()


def test_unknown_study_and_missing_database_are_usage_errors(store, loaded_2x2, tmp_path, capsys) -> None:
    url = store.url.render_as_string(hide_password=False)
    assert main(["export", "--study", "nope", "--out", str(tmp_path / "o"), "--database-url", url]) == 2
    err = capsys.readouterr().err
    assert "no study 'nope' in the store; studies stored: two_by_two" in err
    missing = tmp_path / "absent.sqlite3"
    assert main(["export", "--study", "x", "--out", str(tmp_path / "o"),
                 "--database-url", f"sqlite:///{missing}"]) == 2
    assert "the SQLite file does not exist" in capsys.readouterr().err
    assert not missing.exists() and not (tmp_path / "o").exists()
    assert main(["analyze", "--study", "nope", "--out", str(tmp_path / "o"), "--database-url", url]) == 2
    assert "study nope: no study 'nope' in the store" in capsys.readouterr().err


def test_a_store_of_another_schema_revision_is_refused_with_what_to_do(tmp_path, capsys) -> None:
    from store.migrate import upgrade

    url = f"sqlite:///{tmp_path / 'old.sqlite3'}"
    old = Store(url)
    upgrade(old.engine, "0006")
    old.dispose()
    assert main(["export", "--study", "two_by_two", "--out", str(tmp_path / "o"), "--database-url", url]) == 2
    err = capsys.readouterr().err
    assert "the store's schema is at revision 0006" in err and "start `steakhouse serve` once" in err
    assert "Traceback" not in err and not (tmp_path / "o").exists()


def test_the_analysis_package_imports_nothing_of_the_server() -> None:
    code = ("import sys, analysis.exports.study_export, analysis.pipeline.analyze_study, "
            "analysis.pipeline.study_power; "
            "print(sorted(m for m in sys.modules if m.split('.')[0] in ('server', 'fastapi', 'uvicorn'))); "
            "print('store.tables' in sys.modules)")
    repo = Path(__file__).resolve().parents[3]
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=repo)
    server_modules, reads_the_store = result.stdout.splitlines()
    assert server_modules == "[]"
    assert reads_the_store == "True"


def test_an_export_reads_one_snapshot_while_the_server_writes(store, loaded_2x2) -> None:
    from analysis.source.store_reader import open_engine, read_study

    engine = open_engine(store.url.render_as_string(hide_password=False))
    with engine.connect() as conn:
        before = read_study(conn, "two_by_two")
        join(store, loaded_2x2, "late")  # commits meanwhile: on SQLite the reader holds no write lock
        during = read_study(conn, "two_by_two")
    with engine.connect() as conn:
        after = read_study(conn, "two_by_two")
    engine.dispose()
    assert len(before.participants) == len(during.participants) == 0
    assert [p.recruit_id for p in after.participants] == ["late"]
