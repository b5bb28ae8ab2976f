"""The end-of-study questionnaire (answered once per participant) and where the free-text answers are.

From a stored study's export: ``wide.csv`` holds each analysed participant's end-of-study rating and choice items
and the scores of its named scales (:mod:`analysis.measures.scale_scores`), ``answers.csv`` every answer with its text.

* Rating items and scale scores: n, mean, SD, median, minimum and maximum, over all participants and, in a mixed
  design, per group of the between factor.
* Cronbach's α of each named scale with two items or more, with Feldt's 95 % CI
  (:func:`analysis.statistics.reliability.cronbach`, reverse-coded items reversed): one response per participant, the
  textbook case (the α of an after-trial scale pools several responses of each participant and is reported per
  condition, :mod:`analysis.measures.scale_scores`).
* Choice items: how many participants chose each option.
* Free-text items (after each trial and at the end): how many answers there are, and where (``answers.csv``,
  column ``text``); they are not analysed.

Written to ``end_of_study.csv`` (:data:`END_COLUMNS`) and the report's "Questionnaires at the end of the study"
section.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd

from analysis.measures.scale_scores import reversed_values
from analysis.source.naming import item_key
from analysis.source.study_design import rating_specs
from analysis.statistics.reliability import cronbach
from study_config.study import Design
from study_config.study.design import ItemDesign, QuestionnaireDesign

END_COLUMNS = ["question", "kind", "group", "option", "n", "count", "mean", "sd", "median", "min", "max", "alpha",
               "alpha_ci_low", "alpha_ci_high", "note"]
ALL = "all participants"
END_FILE = "end_of_study.csv"


@dataclass(frozen=True, slots=True, eq=False)
class EndOfStudy:
    table: pd.DataFrame
    """:data:`END_COLUMNS`: one row per rating item, scale score and group; one per choice option and group."""
    free_text: tuple[str, ...]
    """One line per free-text item: ``end.strategy (end of study): 12 answers``."""
    answers_file: str
    """Where the answers are, as the report names it (``data/answers.csv``)."""
    participants: int


def end_of_study(wide: pd.DataFrame, answers: pd.DataFrame, config: Mapping[str, Any],
                 between: Sequence[str] = (), answers_file: str = "answers.csv") -> EndOfStudy | None:
    """The summary of the export's end-of-study answers and free text (``None`` when the study asks neither)."""
    design = Design.from_config(config)
    ratings, scales = rating_specs(design, "end_of_study")
    choices = {item_key(str(q["id"]), str(i["id"])): tuple(str(o) for o in i.get("options", ()))
               for q in config.get("questionnaires") or () if q.get("when") == "end_of_study"
               for i in q.get("items", ()) if i.get("type") == "choice"}
    texts = [(q, i) for q in design.questionnaires for i in q.items if i.type == "text"]
    if not ratings and not choices and not texts:
        return None
    groups: list[tuple[str, pd.DataFrame]] = [(ALL, wide)]
    for factor in (f for f in between if f in wide.columns):
        groups += [(f"{factor}={level}", wide[wide[factor].astype(str) == str(level)])
                   for level in dict.fromkeys(wide[factor].dropna().astype(str))]
    by_column = {item.column: item for item in ratings}
    rows: list[dict[str, object]] = []
    for label, part in groups:
        for item in ratings:
            rows.append(_describe(item.column, "rating", label, part))
        for scale in scales:
            row = _describe(scale.column, "scale", label, part)
            present = [c for c in scale.items if c in part.columns]
            if len(present) >= 2:
                scored = pd.DataFrame({c: reversed_values(part[c].astype(float), by_column[c]) for c in present})
                alpha = cronbach(scored)
                row.update(alpha=alpha["alpha"], alpha_ci_low=alpha["ci95_low"], alpha_ci_high=alpha["ci95_high"],
                           note=alpha["note"])
            else:
                row["note"] = "α needs at least two items"
            rows.append(row)
        for column, options in choices.items():
            values = part[column].dropna().astype(int) if column in part.columns else pd.Series(dtype=int)
            rows += [{"question": column, "kind": "choice", "group": label, "option": option, "n": len(values),
                      "count": int((values == index).sum())} for index, option in enumerate(options)]
    return EndOfStudy(pd.DataFrame(rows, columns=END_COLUMNS), _free_text(answers, texts), answers_file, len(wide))


def _free_text(answers: pd.DataFrame, texts: Sequence[tuple[QuestionnaireDesign, ItemDesign]]) -> tuple[str, ...]:
    """One line per free-text item: how many non-empty answers participants not flagged gave."""
    if len(answers):
        flagged = answers[["test_run", "excluded"]].fillna(0).astype(int).sum(axis=1) > 0
        answers = answers[~flagged]
    lines = []
    for questionnaire, item in texts:
        mine = answers[(answers["questionnaire"] == questionnaire.id) & (answers["item"] == item.id)]
        given = int(mine["text"].fillna("").astype(str).str.strip().ne("").sum())
        when = "end of study" if questionnaire.when == "end_of_study" else "after each main trial"
        lines.append(f"{item_key(questionnaire.id, item.id)} ({when}, “{item.text}”): {given} answer(s)")
    return tuple(lines)


def _describe(column: str, kind: str, group: str, part: pd.DataFrame) -> dict[str, object]:
    values = part[column].dropna().astype(float) if column in part.columns else pd.Series(dtype=float)
    row: dict[str, object] = {"question": column, "kind": kind, "group": group, "n": len(values)}
    if len(values):
        row.update(mean=float(values.mean()), sd=float(values.std(ddof=1)) if len(values) > 1 else np.nan,
                   median=float(values.median()), min=float(values.min()), max=float(values.max()))
    return row
