"""A main trial the server marked low-engagement (played without the participant taking part) is left
out of cells.csv and listed in excluded.csv with its reason, its status is in trials.csv and answers.csv, the
report says how many there were, and --include-invalid keeps it."""

from __future__ import annotations

from steakhouse_store_study import Participant, join, play_participant

from analysis.exports.study_export import export_study
from store import activity
from store.tables import ParticipantRow, TrialRow

REASON = "low_engagement: 0 participant action(s), fewer than 1"


def one_low_engagement_trial(store, loaded) -> tuple[str, str, int]:
    ok, idle = join(store, loaded, "ok"), join(store, loaded, "idle")
    play_participant(store, loaded, ok, Participant(seed=1))
    play_participant(store, loaded, idle, Participant(seed=2))
    with store.transaction() as session:
        second = session.query(TrialRow).filter_by(participant_id=idle, kind="main", index=1).one()
        measured = activity.measure(session, second.id, 5.0)
        activity.record(session, second.id, measured, REASON)
        names = {pid: session.get(ParticipantRow, pid).public_id for pid in (ok, idle)}
        return names[ok], names[idle], second.id


def test_a_low_engagement_trial_is_listed_and_kept_out_of_the_cells(store, loaded_2x2, tmp_path):
    ok, idle, low_id = one_low_engagement_trial(store, loaded_2x2)
    tables = export_study(store.engine, "two_by_two", tmp_path).dataset.tables
    cells = tables["cells.csv"]
    assert low_id not in set(cells["trial_id"])
    assert cells.groupby("participant").size().to_dict() == {ok: 4, idle: 3}
    [row] = tables["excluded.csv"].itertuples()
    assert (row.participant, row.category, row.in_cells) == (idle, "low_engagement", 1)
    assert row.reason.endswith(f"(main trial 2 invalid: {REASON})")
    trials_csv = tables["trials.csv"].set_index("trial_id")
    listed = trials_csv.loc[low_id]
    assert (listed["trial_status"], listed["engagement_reason"], listed["in_cells"]) == ("low_engagement", REASON, 0)
    # The activity the store counted agrees with the export's own measures of the same trial.
    main = trials_csv[trials_csv["kind"] == "main"]
    assert set(main["trial_status"]) == {"finished", "low_engagement"}
    counted = main.loc[low_id]
    assert counted["delivered_by_participant"] + counted["delivered_by_robot"] == counted["delivered"]
    answers = tables["answers.csv"]
    assert set(answers.loc[answers["trial_id"] == low_id, "trial_status"]) == {"low_engagement"}
    kept = export_study(store.engine, "two_by_two", tmp_path / "kept", include_invalid=True).dataset.tables
    assert low_id in set(kept["cells.csv"]["trial_id"])


def test_the_report_says_how_many_trials_were_low_engagement(store, loaded_2x2, tmp_path):
    from analysis.pipeline.analyze_study import analyze_study

    _, idle, low_id = one_low_engagement_trial(store, loaded_2x2)
    default = analyze_study(store.engine, "two_by_two", tmp_path / "default", ["ticks"], plots=False)
    assert low_id not in set(default.cells["trial_id"])
    report = (tmp_path / "default" / "report.md").read_text()
    assert "1 main trial(s) were low-engagement" in report and "left out of the analysis" in report
    assert f"participant {idle}, main trial 2" in report
    kept = analyze_study(store.engine, "two_by_two", tmp_path / "kept", ["ticks"],
                         include={"invalid", "low_engagement"}, plots=False)
    assert low_id in set(kept.cells["trial_id"])
    assert "are kept (--include-invalid)" in (tmp_path / "kept" / "report.md").read_text()
