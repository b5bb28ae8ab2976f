"""Every study that validates exports and analyses: a study with every item type (rating, reverse-coded rating,
choice, free text) in every questionnaire position (after each trial, end of study), each with a named scale,
goes through ``steakhouse export``, ``steakhouse analyze --study`` and the admin ``export.zip``; every column of
every file is in the data dictionary and nothing else is; the scale scores are in ``cells.csv`` and ``wide.csv``."""

from __future__ import annotations

import csv
import io
import zipfile

import httpx
import pandas as pd
import pytest
from pydantic import SecretStr
from steakhouse_store_study import Participant, current_step, join, play_stored_trial
from steakhouse_testing import ThreadServer, write_study

from analysis.exports.dataset import FILES
from analysis.exports.spss import SAV_FILE
from analysis.exports.study_export import DICTIONARY_FILES, export_study
from server.cli import main
from server.flow import service
from store.engine import Store
from store.studies import sync_study
from study_config.catalog import load_one

STUDY = "every_item"
AFTER_TRIAL = {"id": "post", "items": [
    {"id": "fluency", "text": "Fluent.", "scale": {"min": 1, "max": 7, "labels": {1: "Not at all", 7: "Very"}}},
    {"id": "effort", "text": "Effort.", "scale": {"min": 1, "max": 7}, "reverse": True},
    {"id": "hand", "type": "choice", "text": "Hand?", "options": ["Left", "Right"]},
    {"id": "comment", "type": "text", "text": "Anything?", "required": False},
], "scales": [{"id": "team", "title": "Teamwork", "items": ["fluency", "effort"]}]}
END = {"id": "end", "when": "end_of_study", "items": [
    {"id": "liking", "text": "Liked it.", "scale": {"min": 1, "max": 5}},
    {"id": "ease", "text": "Hard.", "scale": {"min": 1, "max": 5}, "reverse": True},
    {"id": "device", "type": "choice", "text": "Device?", "options": ["Mouse", "Trackpad", "Other"]},
    {"id": "strategy", "type": "text", "text": "Any comments?"},
], "scales": [{"id": "experience", "title": "Experience", "items": ["liking", "ease"]}]}
PEOPLE = 4


def answers_for(questionnaire: str, person: int, trial: int) -> dict[str, object]:
    if questionnaire == "post":
        return {"fluency": 1 + (person + 2 * trial) % 7, "effort": 1 + (3 * person + trial) % 7,
                "hand": (person + trial) % 2, "comment": f"=trial {trial}, person {person}"}
    return {"liking": 1 + person % 5, "ease": 5 - person % 3, "device": person % 3,
            "strategy": f'I waited, then "stopped", then went on {person}'}


@pytest.fixture(scope="module")
def stored(module_db_url, tmp_path_factory):
    store = Store(module_db_url)
    store.migrate()
    path = write_study(tmp_path_factory.mktemp("studies"), STUDY, robots=["stay", "baseline"],
                       kitchens=["practice"], factors=["robot"], world={"orders": 1, "horizon": 30, "kb_delay": 1},
                       questionnaires=[AFTER_TRIAL, END])
    loaded = load_one(path)
    with store.transaction() as session:
        sync_study(session, loaded.study)
    for person in range(PEOPLE):
        pid = join(store, loaded, f"r{person}")
        trial = 0
        while (step := current_step(store, pid).current).kind in ("trial", "questionnaire"):
            if step.kind == "trial":
                play_stored_trial(store, loaded, pid, Participant(seed=person))
                trial += 1
            else:
                service.submit_questionnaire(store, loaded, pid, step.questionnaire,
                                             answers_for(step.questionnaire, person, trial))
    store.dispose()
    return module_db_url, path


def test_export_writes_every_file_with_every_column_in_the_dictionary(stored, tmp_path):
    url, _ = stored
    result = export_study(url, STUDY, tmp_path)
    with (tmp_path / DICTIONARY_FILES[1]).open(newline="", encoding="utf-8") as handle:
        documented = list(csv.DictReader(handle))
    for name in FILES:
        header = list(pd.read_csv(tmp_path / name, nrows=0).columns)
        assert header == [r["column"] for r in documented if r["file"] == name], name
    cells = pd.read_csv(tmp_path / "cells.csv")
    wide = pd.read_csv(tmp_path / "wide.csv")
    assert len(cells) == 2 * PEOPLE and len(wide) == PEOPLE
    assert {"post.fluency", "post.effort", "post.hand", "post.team"} <= set(cells.columns)
    assert not {c for c in [*cells.columns, *wide.columns] if "comment" in c or "strategy" in c}, "text: answers.csv"
    assert {"end.liking", "end.ease", "end.device", "end.experience", "post.team__stay__practice",
            "post.hand__baseline__practice"} <= set(wide.columns)
    # scale scores: the mean of the items after reversing the reverse-coded one (min + max − value)
    assert cells["post.team"].tolist() == pytest.approx(((cells["post.fluency"] + 8 - cells["post.effort"]) / 2)
                                                        .tolist())
    assert wide["end.experience"].tolist() == pytest.approx(((wide["end.liking"] + 6 - wide["end.ease"]) / 2)
                                                            .tolist())
    answers = pd.read_csv(tmp_path / "answers.csv", keep_default_na=False)
    strategies = answers[answers["item"] == "strategy"]["text"].tolist()
    assert strategies == [f'I waited, then "stopped", then went on {p}' for p in range(PEOPLE)]
    comments = answers[answers["item"] == "comment"]["text"]
    assert len(comments) == 2 * PEOPLE and all(c.startswith("'=trial") for c in comments)
    assert result.dataset.columns["wide.csv"][-1].name == "end.experience"


def test_spss_users_get_wide_sav_with_variable_and_value_labels(stored, tmp_path):
    import pyreadstat

    url, _ = stored
    result = export_study(url, STUDY, tmp_path)
    assert tmp_path / SAV_FILE in result.files
    sav, meta = pyreadstat.read_sav(str(tmp_path / SAV_FILE))
    wide = pd.read_csv(tmp_path / "wide.csv")
    assert list(sav.columns) == list(wide.columns)
    pd.testing.assert_frame_equal(sav.drop(columns="participant"), wide.drop(columns="participant").astype(float))
    assert sav["participant"].tolist() == wide["participant"].astype(str).tolist()
    assert meta.variable_value_labels["post.hand__stay__practice"] == {0.0: "Left", 1.0: "Right"}
    assert meta.variable_value_labels["post.fluency__baseline__practice"] == {1.0: "Not at all", 7.0: "Very"}
    assert meta.variable_value_labels["end.device"] == {0.0: "Mouse", 1.0: "Trackpad", 2.0: "Other"}
    assert meta.variable_value_labels["complete"] == {0.0: "no", 1.0: "yes"}
    labels = dict(zip(meta.column_names, meta.column_labels, strict=True))
    label = labels["end.experience"]
    assert label is not None and label.startswith("scale score “Experience”")


def test_analyze_runs_on_the_study_and_analyses_the_after_trial_scale(stored, tmp_path, capsys):
    url, _ = stored
    out = tmp_path / "results"
    assert main(["analyze", "--study", STUDY, "--out", str(out), "--database-url", url, "--no-plots"]) == 0
    anova = pd.read_csv(out / "anova.csv")
    assert "post.team" in set(anova["measure"]), "the after-trial scale is analysed by default"
    assert (out / "data" / "wide.csv").is_file() and (out / "report.md").is_file()


def test_the_report_covers_the_end_of_study_questionnaire_and_says_where_free_text_is(stored, tmp_path):
    """Descriptives of every end-of-study rating and scale, the scale's textbook α (one response per participant,
    the reversed item reversed) as pingouin computes it, the choices counted, and the free-text answers counted and
    located."""
    import pingouin as pg

    url, _ = stored
    out = tmp_path / "results"
    assert main(["analyze", "--study", STUDY, "--out", str(out), "--database-url", url, "--no-plots"]) == 0
    end = pd.read_csv(out / "end_of_study.csv")
    wide = pd.read_csv(out / "data" / "wide.csv")
    liking = end[end["question"] == "end.liking"].iloc[0]
    assert (liking["n"], liking["mean"], liking["sd"]) == (PEOPLE, pytest.approx(wide["end.liking"].mean()),
                                                           pytest.approx(wide["end.liking"].std()))
    scale = end[end["question"] == "end.experience"].iloc[0]
    alpha, _ = pg.cronbach_alpha(pd.DataFrame({"liking": wide["end.liking"], "ease": 6 - wide["end.ease"]}))
    assert scale["alpha"] == pytest.approx(alpha, rel=1e-12)
    device = end[end["question"] == "end.device"].set_index("option")["count"].to_dict()
    assert device == {o: int((wide["end.device"] == i).sum()) for i, o in enumerate(["Mouse", "Trackpad", "Other"])}
    report = (out / "report.md").read_text(encoding="utf-8")
    section = report.split("## Questionnaires at the end of the study, and free text")[1].split("\n## ")[0]
    assert "| end.experience | all participants | 4 |" in section
    assert "| end.device | all participants | Mouse |" in section
    assert "they are in data/answers.csv (column text" in section
    assert "- end.strategy (end of study, “Any comments?”): 4 answer(s)" in section
    assert f"- post.comment (after each main trial, “Anything?”): {2 * PEOPLE} answer(s)" in section


def test_the_admin_zip_holds_the_same_export(stored, tmp_path):
    from server.app import create_app
    from server.settings import Settings

    url, path = stored
    app = create_app(Settings(database_url=url, study_files=(path,), robot_workers=0,
                              admin_token=SecretStr("admin-secret"), static_dir=tmp_path / "no-static"))
    with ThreadServer(app) as server, httpx.Client(base_url=server.url, timeout=60) as client:
        response = client.get(f"/api/admin/studies/{STUDY}/export.zip",
                              headers={"Authorization": "Bearer admin-secret"})
    assert response.status_code == 200, response.text
    archive = zipfile.ZipFile(io.BytesIO(response.content))
    assert set(archive.namelist()) == {f"{STUDY}_export/{n}" for n in (*FILES, SAV_FILE, *DICTIONARY_FILES)}
    direct = export_study(url, STUDY, tmp_path / "direct")
    for name in ("cells.csv", "wide.csv", "answers.csv"):
        zipped = pd.read_csv(archive.open(f"{STUDY}_export/{name}"))
        pd.testing.assert_frame_equal(zipped, pd.read_csv(direct.out_dir / name), check_dtype=False)
