"""Questionnaire items of every type (rating, free text, single choice), reverse-coded ratings and named
scales: valid ones load, invalid ones are refused naming the file, the field and the reason."""

from __future__ import annotations

import textwrap
from pathlib import Path

from study_config.study import load_study, validate_study_file

BASE = """\
id: t
title: Items
kitchens: [none_3]
robots: [stay]
factors: [robot]
questionnaires:
  - id: post
    items:
"""


def problems(tmp_path: Path, items: str, scales: str = "") -> list[tuple[str, str]]:
    path = tmp_path / "study.yaml"
    path.write_text(BASE + textwrap.indent(textwrap.dedent(items), " " * 6)
                    + (textwrap.indent(textwrap.dedent(scales), " " * 4) if scales else ""), encoding="utf-8")
    return [(p.path, p.reason) for p in validate_study_file(path)]


GOOD = """\
- {id: fluency, text: Fluent., scale: {min: 1, max: 7}}
- {id: effort, text: Effort., scale: {min: 1, max: 7}, reverse: true}
- {id: comment, type: text, text: "Anything else?", required: false, min_length: 3, max_length: 500}
- {id: hand, type: choice, text: "Which hand do you use the mouse with?", options: [Left, Right, Both]}
"""


def test_every_item_type_loads_with_its_settings(tmp_path):
    assert problems(tmp_path, GOOD, "scales:\n  - {id: fluent_team, title: Fluency, items: [fluency, effort]}\n") == []
    study = load_study(tmp_path / "study.yaml")
    (questionnaire,) = study.questionnaires
    fluency, effort, comment, hand = questionnaire.items
    assert (fluency.type, fluency.reverse, effort.reverse) == ("rating", False, True)
    assert (comment.type, comment.min_length, comment.max_length, comment.scale) == ("text", 3, 500, None)
    assert (hand.type, hand.options) == ("choice", ("Left", "Right", "Both"))
    assert questionnaire.scales[0].items == ("fluency", "effort")
    assert questionnaire.item("comment") is comment and questionnaire.item("nope") is None


def test_a_text_items_length_limit_defaults_to_2000_and_is_capped(tmp_path):
    assert problems(tmp_path, "- {id: c, type: text, text: 'C?'}\n") == []
    assert load_study(tmp_path / "study.yaml").questionnaires[0].items[0].max_length == 2000
    found = problems(tmp_path, "- {id: c, type: text, text: 'C?', max_length: 20000}\n")
    assert found == [("questionnaires[0].items[0].max_length", "should be less than or equal to 10000 (got 20000)")]


def test_settings_of_another_item_type_are_refused(tmp_path):
    found = problems(tmp_path, """\
        - {id: a, type: text, text: "A?", scale: {min: 1, max: 5}}
        - {id: b, type: choice, text: "B?", options: [x, y], reverse: true}
        - {id: c, text: C., scale: {min: 1, max: 5}, options: [x, y], max_length: 10}
        """)
    assert found == [
        ("questionnaires[0].items[0].scale", "only used by rating items, not by a text item"),
        ("questionnaires[0].items[1].reverse", "only used by rating items, not by a choice item"),
        ("questionnaires[0].items[2].options", "only used by choice items, not by a rating item"),
        ("questionnaires[0].items[2].max_length", "only used by text items, not by a rating item"),
    ]


def test_incomplete_items_name_what_is_missing(tmp_path):
    found = problems(tmp_path, """\
        - {id: a, text: A.}
        - {id: b, type: choice, text: "B?", options: [only]}
        - {id: c, type: choice, text: "C?", options: [x, y, x]}
        - {id: d, type: text, text: "D?", min_length: 50, max_length: 10}
        - {id: e, type: essay, text: "E?"}
        """)
    assert found[:4] == [
        ("questionnaires[0].items[0].scale",
         "required field is missing (a rating item needs a scale {min, max, labels})"),
        ("questionnaires[0].items[1].options", "a choice item needs at least two options"),
        ("questionnaires[0].items[2].options[2]", "duplicate option 'x' (already at [0])"),
        ("questionnaires[0].items[3].min_length", "min_length (50) is above max_length (10)"),
    ]
    assert found[4][0] == "questionnaires[0].items[4].type" and "'rating', 'text' or 'choice'" in found[4][1]


def test_scales_combine_rating_items_on_one_range_of_their_own_questionnaire(tmp_path):
    found = problems(tmp_path, GOOD + "- {id: wide, text: Wide., scale: {min: 0, max: 10}}\n", """\
        scales:
          - {id: one, items: [fluency, ghost, comment]}
          - {id: two, items: [fluency, wide, fluency]}
          - {id: fluency, items: [effort]}
          - {id: one, items: [effort]}
        """)
    assert found == [
        ("questionnaires[0].scales[0].items[1]",
         "no item 'ghost' in this questionnaire; items are: fluency, effort, comment, hand, wide"),
        ("questionnaires[0].scales[0].items[2]", "item 'comment' is a text item; scales combine rating items"),
        ("questionnaires[0].scales[1].items", "items of one scale must share one rating range (found 0..10, 1..7)"),
        ("questionnaires[0].scales[1].items[2]", "duplicate item 'fluency' (already at [0])"),
        ("questionnaires[0].scales[2].id",
         "'fluency' is also an item id; exports name both <questionnaire>.<id>, so give the scale another id"),
        ("questionnaires[0].scales[3].id", "duplicate scale id 'one' (already at [0])"),
    ]
