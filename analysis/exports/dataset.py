"""The export's tables, built from one study's stored rows (see :mod:`analysis.exports.dictionary` for the columns).

Which trial enters the statistics: for each participant and main trial, the latest attempt that
``finished`` (delivered or horizon). Practice trials, abandoned or running attempts and the trials of
participants flagged as test runs or excluded are exported in ``ticks.csv`` / ``trials.csv`` with their flags,
never in ``cells.csv``. Flagged participants, and participants missing a cell, are listed in
``excluded.csv`` with the reason (nothing is dropped silently). Main trials the server marked invalid are
left out of ``cells.csv`` unless ``include_invalid`` (their reason is in ``trials.csv`` and ``excluded.csv``).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import pandas as pd
from sqlalchemy import Connection

from analysis.exports.dictionary import (
    ANSWER_COLUMNS,
    CELL_COLUMNS,
    EXCLUDED_COLUMNS,
    FLAG,
    INT,
    TICK_COLUMNS,
    TRIAL_COLUMNS,
    Column,
    participant_columns,
    wide_column,
    wide_columns,
)
from analysis.exports.export_design import ExportDesign
from analysis.exports.roster import Used, excluded_row, participant_row, used_trials
from analysis.measures.participation import participation_values, trial_status
from analysis.measures.scale_scores import response_scores
from analysis.measures.trial_measures import TRIAL_MEASURES, trial_measures
from analysis.measures.work import redundant_action_flags, subtask_switch_flags
from analysis.source.naming import item_key as item_column
from analysis.source.store_reader import (
    StoredParticipant,
    StoredTick,
    StoredTrial,
    iso_time,
    read_events,
    read_study,
    read_ticks,
)
from analysis.source.study_design import ScaleSpec
from planner.summary import GAP_COMPONENTS
from study_config.study.fov_angles import angle_value

FILES = ("ticks.csv", "trials.csv", "cells.csv", "wide.csv", "answers.csv", "participants.csv", "excluded.csv")


@dataclass(frozen=True, slots=True, eq=False)
class Dataset:
    """One study's export: ``tables[file]`` with the documented ``columns[file]``."""

    study_id: str
    design: ExportDesign
    tables: dict[str, pd.DataFrame]
    columns: dict[str, tuple[Column, ...]]
    config: Mapping[str, Any] = field(default_factory=dict)
    """The study's resolved configuration as stored (the analysis reads factors, levels and scales from it; the
    data dictionary its questionnaire items and scales)."""
    pilots_left_out: int = 0
    """Simulated pilot participants in the store that the export left out (exported only with ``include_pilot``)."""

    @property
    def cells(self) -> pd.DataFrame:
        return self.tables["cells.csv"]

    @property
    def excluded(self) -> pd.DataFrame:
        return self.tables["excluded.csv"]


def build_dataset(conn: Connection, study_id: str, include_invalid: bool = False,
                  include_pilot: bool = False) -> Dataset:
    """Read the study from the store and build every table of the export (invalid main trials in
    ``cells.csv`` only with ``include_invalid``; simulated pilot participants only with ``include_pilot``)."""
    data = read_study(conn, study_id, include_pilot)
    design = ExportDesign.from_config(data.config)
    events = read_events(conn, study_id)
    people = {p.id: p for p in data.participants}
    tick_rows: list[dict[str, Any]] = []
    measures: dict[int, dict[str, Any]] = {}
    stored: dict[int, int] = {}
    for trial in data.trials:
        ticks = read_ticks(conn, trial.id)
        measures[trial.id] = trial_measures(trial, ticks, events.get(trial.id, []))
        stored[trial.id] = len(ticks)
        tick_rows += _tick_rows(people[trial.participant_id].public_id, trial, ticks)
    used = used_trials(data.trials, people, include_invalid)
    answers = _answers_by_participant(data.answers)
    columns = export_columns(design)
    cell_rows = [row for p in data.participants if p.id in used
                 for row in _cell_rows(p, used[p.id], measures, answers.get(p.id, {}), design)]
    trial_rows = [_trial_row(people[t.participant_id], t, measures[t.id], stored[t.id], used) for t in data.trials]
    rows = {
        "ticks.csv": tick_rows,
        "trials.csv": trial_rows,
        "cells.csv": cell_rows,
        "wide.csv": _wide_rows(data.participants, cell_rows, answers, design),
        "answers.csv": _answer_rows(data, people, design),
        "participants.csv": [participant_row(p, data.trials, used, design) for p in data.participants],
        "excluded.csv": [row for p in data.participants
                         if (row := excluded_row(p, data.trials, used, design)) is not None],
    }
    tables = {name: _frame(rows[name], columns[name]) for name in FILES}
    return Dataset(study_id, design, tables, columns, data.config, data.pilots_left_out)


def export_columns(design: ExportDesign) -> dict[str, tuple[Column, ...]]:
    """The columns of every exported file, in order: the one definition both the tables and the data dictionary
    are built from (the questionnaire columns are :attr:`ExportDesign.trial_value_columns` / ``end_value_columns``)."""
    per_cell = [*(c for c in CELL_COLUMNS if c.name in TRIAL_MEASURES), *design.trial_value_columns]
    return {
        "ticks.csv": TICK_COLUMNS,
        "trials.csv": TRIAL_COLUMNS,
        "cells.csv": (*CELL_COLUMNS, *design.trial_value_columns),
        "wide.csv": tuple(wide_columns(per_cell, design.within_cells, design.end_value_columns,
                                       design.within_fields, design.between)),
        "answers.csv": ANSWER_COLUMNS,
        "participants.csv": participant_columns(design.between),
        "excluded.csv": EXCLUDED_COLUMNS,
    }


def _frame(rows: list[dict[str, Any]], columns: Sequence[Column]) -> pd.DataFrame:
    names = [c.name for c in columns]
    undocumented = set().union(*rows) - set(names) if rows else set()
    if undocumented:
        raise RuntimeError(f"columns missing from the data dictionary: {sorted(undocumented)}")
    frame = pd.DataFrame(rows, columns=names)
    for column in columns:
        if column.type in (INT, FLAG):
            frame[column.name] = pd.array(
                [None if _missing(v) else int(v) for v in frame[column.name]], dtype="Int64")
    return frame


def _missing(value: Any) -> bool:
    return value is None or (isinstance(value, float) and value != value)


def _events_text(events: list[dict[str, Any]] | None) -> str | None:
    if events is None:
        return None
    return ";".join(f"{e.get('agent')}:{e.get('kind')}" for e in events)


def _statuses(summary: dict[str, Any], key: str) -> str:
    value = summary.get(key)
    return "|".join(str(v) for v in value) if isinstance(value, list) else ("" if value is None else str(value))


def _tick_rows(participant: str, trial: StoredTrial, ticks: Sequence[StoredTick]) -> list[dict[str, Any]]:
    switches = subtask_switch_flags([t.subtask for t in ticks], [t.controller for t in ticks])
    redundant = redundant_action_flags(trial.initial_state, [t.world_state for t in ticks])
    rows = []
    for tick, switch, extra in zip(ticks, switches, redundant, strict=True):
        world, kb = tick.world_summary, tick.kb_summary
        row: dict[str, Any] = {
            "participant": participant, "trial_id": trial.id, "kind": trial.kind, "index": trial.index,
            "attempt": trial.attempt, "robot": trial.robot, "kitchen": trial.kitchen, "view": trial.view,
            "fov_angle": angle_value(trial.fov_angle), "tick": tick.tick,
            "human_action": tick.human_action, "robot_action": tick.robot_action,
            "action_source": tick.action_source, "subtask": tick.subtask, "subtask_switch": switch,
            "redundant_action": extra, "human_held": tick.world_state.get("human", {}).get("held"),
            "robot_held": world.get("robot_held"), "grill": _statuses(world, "grill"),
            "board": _statuses(world, "board"), "sink": _statuses(world, "sink"),
            "kb_robot_held": kb.get("robot_held"), "kb_grill": _statuses(kb, "grill"),
            "kb_board": _statuses(kb, "board"), "kb_sink": _statuses(kb, "sink"),
            "kb_gap_total": tick.kb_gap_total, "robot_in_fov": int(tick.robot_in_fov),
            "lateness_ms": tick.lateness_ms, "decision_ms": tick.decision_ms,
            "robot_missed": int(tick.robot_missed), "recorded_at": iso_time(tick.recorded_at),
            "round_seconds": tick.round_seconds,
            "world_events": _events_text(tick.world_events),
        }
        diff = tick.kb_diff or {}
        row["kb_diff_total"] = sum(diff.values()) if tick.kb_diff is not None else None
        for component in GAP_COMPONENTS:
            row[f"kb_diff_{component}"] = diff.get(component)
            row[f"kb_gap_{component}"] = int(tick.kb_gap.get(component, 0))
        rows.append(row)
    return rows


def _answers_by_participant(answers: Iterable[Any]) -> dict[int, dict[int | None, dict[str, int | None]]]:
    """Participant id → main trial index (``None``: end of study) → item column → value."""
    out: dict[int, dict[int | None, dict[str, int | None]]] = {}
    for a in answers:
        out.setdefault(a.participant_id, {}).setdefault(a.after_trial, {})[
            item_column(a.questionnaire_id, a.item_id)] = a.value
    return out


def _cell_rows(p: StoredParticipant, used: dict[int, StoredTrial], measures: dict[int, dict[str, Any]],
               answers: dict[int | None, dict[str, int | None]], design: ExportDesign) -> list[dict[str, Any]]:
    rows = []
    for index, trial in sorted(used.items()):
        row: dict[str, Any] = {"participant": p.public_id, "robot": trial.robot, "kitchen": trial.kitchen,
                               "view": trial.view, "fov_angle": angle_value(trial.fov_angle),
                               "condition": trial.condition, "trial_id": trial.id, "position": index + 1}
        row.update({m: measures[trial.id][m] for m in TRIAL_MEASURES})
        row.update(_questionnaire_values(answers.get(index, {}), design.trial_items, design.trial_scales, design))
        rows.append(row)
    return rows


def _questionnaire_values(given: Mapping[str, int | None], items: tuple[tuple[str, str, str], ...],
                          scales: tuple[ScaleSpec, ...], design: ExportDesign) -> dict[str, Any]:
    """The questionnaire columns of one response: each rating or choice item of ``items`` as answered, then each
    scale's score (free-text answers are not among them: they are in ``answers.csv``)."""
    values: dict[str, Any] = {name: given.get(name) for name in design.item_names(items)}
    return {**values, **response_scores(values, design.ratings, scales)} if scales else values


def _trial_row(p: StoredParticipant, trial: StoredTrial, measures: dict[str, Any], stored: int,
               used: Used) -> dict[str, Any]:
    in_cells = used.get(p.id, {}).get(trial.index) is trial if trial.kind == "main" else False
    return {
        "participant": p.public_id, "trial_id": trial.id, "kind": trial.kind, "index": trial.index,
        "attempt": trial.attempt, "condition": trial.condition, "robot": trial.robot, "kitchen": trial.kitchen,
        "view": trial.view, "fov_angle": angle_value(trial.fov_angle), "seed": trial.seed, "status": trial.status,
        "end_reason": trial.end_reason,
        "started_at": iso_time(trial.started_at), "ended_at": iso_time(trial.ended_at),
        "config_hash": trial.config_hash,
        "in_cells": int(in_cells), "participant_test_run": int(p.test_run), "participant_excluded": int(p.excluded),
        **measures, "ticks_stored": stored, "decisions": trial.decisions,
        "missed_decisions": trial.missed_decisions,
        "missed_decisions_pct": (round(100.0 * trial.missed_decisions / trial.decisions, 2)
                                 if trial.decisions and trial.missed_decisions is not None else None),
        "invalid_reason": trial.invalid_reason, **participation_values(trial),
    }


def _wide_rows(participants: Sequence[StoredParticipant], cell_rows: list[dict[str, Any]],
               answers: dict[int, dict[int | None, dict[str, int | None]]],
               design: ExportDesign) -> list[dict[str, Any]]:
    values = [*TRIAL_MEASURES, *(c.name for c in design.trial_value_columns)]
    by_participant: dict[str, list[dict[str, Any]]] = {}
    for cell_row in cell_rows:
        by_participant.setdefault(cell_row["participant"], []).append(cell_row)
    out = []
    for p in participants:
        cells = by_participant.get(p.public_id)
        if not cells:
            continue
        row: dict[str, Any] = {"participant": p.public_id, **design.group_of(p.condition_order),
                               "order_index": p.order_index}
        present = {design.cell_of(c["robot"], c["kitchen"], c["view"], c["fov_angle"]) for c in cells}
        row["complete"] = int(all(cond in present for cond in design.expected_cells(p.condition_order)))
        for cell in cells:
            levels = design.within_cell(design.cell_of(cell["robot"], cell["kitchen"], cell["view"],
                                                       cell["fov_angle"]))
            for name in values:
                row[wide_column(name, *levels)] = cell[name]
        row.update(_questionnaire_values(answers.get(p.id, {}).get(None, {}), design.end_items, design.end_scales,
                                         design))
        out.append(row)
    return out


def _answer_rows(data: Any, people: dict[int, StoredParticipant], design: ExportDesign) -> list[dict[str, Any]]:
    trials = {t.id: t for t in data.trials}
    rows = []
    for a in data.answers:
        p = people[a.participant_id]
        condition = None
        if a.after_trial is not None and a.after_trial < len(p.condition_order):
            condition = p.condition_order[a.after_trial]
        trial = trials.get(a.trial_id) if a.trial_id is not None else None
        robot_kitchen = (trial.robot, trial.kitchen) if trial else (
            design.condition_of(condition) if condition else None)
        rows.append({
            "participant": p.public_id, "questionnaire": a.questionnaire_id, "item": a.item_id, "value": a.value,
            "text": a.text,
            "after_trial": a.after_trial, "trial_status": trial_status(trial) if trial else None,
            "condition": trial.condition if trial else condition,
            "robot": robot_kitchen[0] if robot_kitchen else None,
            "kitchen": robot_kitchen[1] if robot_kitchen else None,
            "view": trial.view if trial else None, "fov_angle": angle_value(trial.fov_angle) if trial else None,
            "trial_id": a.trial_id,
            "answered_at": iso_time(a.created_at), "test_run": int(p.test_run), "excluded": int(p.excluded),
        })
    return rows
