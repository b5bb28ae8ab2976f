"""A main trial the server marked invalid (robot decisions past their deadline) is listed in excluded.csv with
its reason and left out of cells.csv, unless the export is asked to include invalid trials."""

from __future__ import annotations

import pandas as pd
from steakhouse_store_study import Participant, join, play_participant

from analysis.exports.study_export import export_study
from server.cli import main
from store import trials
from store.tables import ParticipantRow, TrialRow

REASON = "robot decisions missed their deadline: 40 of 120 (33.3 % > 5 %)"


def two_participants_one_invalid_trial(store, loaded) -> tuple[str, str, int]:
    ok, hit = join(store, loaded, "ok"), join(store, loaded, "hit")
    play_participant(store, loaded, ok, Participant(seed=1))
    play_participant(store, loaded, hit, Participant(seed=2))
    with store.transaction() as session:
        second = session.query(TrialRow).filter_by(participant_id=hit, kind="main", index=1).one()
        trials.record_health(session, second.id, decisions=120, missed=40, invalid_reason=REASON)
        names = {pid: session.get(ParticipantRow, pid).public_id for pid in (ok, hit)}
        return names[ok], names[hit], second.id


def test_an_invalid_trial_is_listed_with_its_reason_and_kept_out_of_the_cells(store, loaded_2x2, tmp_path):
    ok, hit, invalid_id = two_participants_one_invalid_trial(store, loaded_2x2)
    result = export_study(store.engine, "two_by_two", tmp_path)
    tables = result.dataset.tables
    cells = tables["cells.csv"]
    assert invalid_id not in set(cells["trial_id"])
    assert (cells.groupby("participant").size().to_dict()) == {ok: 4, hit: 3}
    [row] = tables["excluded.csv"].itertuples()
    assert (row.participant, row.category, row.in_cells) == (hit, "invalid", 1)
    assert row.reason.endswith(f"(main trial 2 invalid: {REASON})")
    listed = tables["trials.csv"].set_index("trial_id").loc[invalid_id]
    assert (listed["invalid_reason"], listed["missed_decisions_pct"], listed["in_cells"]) == (REASON, 33.33, 0)


def test_include_invalid_keeps_the_trial_in_the_cells(store, loaded_2x2, tmp_path, capsys):
    _ok, _hit, invalid_id = two_participants_one_invalid_trial(store, loaded_2x2)
    url = store.url.render_as_string(hide_password=False)
    assert main(["export", "--study", "two_by_two", "--out", str(tmp_path), "--database-url", url,
                 "--include-invalid"]) == 0
    cells = pd.read_csv(tmp_path / "cells.csv")
    assert invalid_id in set(cells["trial_id"]) and len(cells) == 8
    assert pd.read_csv(tmp_path / "excluded.csv").empty
    trials_csv = pd.read_csv(tmp_path / "trials.csv").set_index("trial_id")
    assert trials_csv.loc[invalid_id, "in_cells"] == 1 and trials_csv.loc[invalid_id, "invalid_reason"] == REASON


def test_the_analysis_leaves_the_invalid_trial_out_by_default_and_names_it(store, loaded_2x2, tmp_path):
    from analysis.pipeline.analyze_study import analyze_study

    _, hit, invalid_id = two_participants_one_invalid_trial(store, loaded_2x2)
    default = analyze_study(store.engine, "two_by_two", tmp_path / "default", ["ticks"], plots=False)
    kept = analyze_study(store.engine, "two_by_two", tmp_path / "kept", ["ticks"], include={"invalid"}, plots=False)
    assert invalid_id not in set(default.cells["trial_id"]) and invalid_id in set(kept.cells["trial_id"])
    report = (tmp_path / "default" / "report.md").read_text()
    assert f"participant {hit}, main trial 2" in report and REASON in report
