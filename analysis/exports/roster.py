"""Who is in the analysis and who is not, and why: the trial attempt each cell uses, participants.csv and
excluded.csv rows.

A cell uses, for each participant and main trial, the latest attempt that ``finished`` (all orders delivered
or the horizon reached). Participants flagged as test runs or excluded by the experimenter have no cells; a
participant without a cell in some condition is listed as ``incomplete`` with the reason for each missing
cell (not played yet, abandoned, still running, not in their order). A main trial the server marked invalid
(robot decisions past their deadline, ``server.game.health``) or ``low_engagement`` (the participant did not take
part, ``server.flow.engagement``) has no cell unless the export includes invalid trials; its participant is
listed as ``invalid`` (``low_engagement`` when that is the only reason) with the trial's reason.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from typing import Any

from analysis.exports.export_design import ExportDesign
from analysis.source.naming import cell_label
from analysis.source.store_reader import StoredParticipant, StoredTrial, iso_time

INVALID_MARK = "invalid"
LOW_ENGAGEMENT = "low_engagement"
"""The start of the server's reason for a low-engagement trial (``server.flow.engagement``)."""
Used = dict[int, dict[int, StoredTrial]]
"""Participant id → main trial index → the attempt in cells.csv."""


def flagged(p: StoredParticipant) -> bool:
    return p.test_run or p.excluded


def used_trials(trials: Sequence[StoredTrial], people: dict[int, StoredParticipant],
                include_invalid: bool = False) -> Used:
    """The attempt each cell uses (flagged participants have none; invalid trials only with
    ``include_invalid``)."""
    used: Used = {}
    for trial in trials:
        if trial.kind != "main" or trial.status != "finished" or flagged(people[trial.participant_id]):
            continue
        if trial.invalid and not include_invalid:
            continue
        mine = used.setdefault(trial.participant_id, {})
        if trial.index not in mine or trial.attempt > mine[trial.index].attempt:
            mine[trial.index] = trial
    return used


def participant_row(p: StoredParticipant, trials: Sequence[StoredTrial], used: Used,
                    design: ExportDesign) -> dict[str, Any]:
    """The participant's participants.csv row."""
    mine = [t for t in trials if t.participant_id == p.id and t.status == "finished"]
    return {
        "participant": p.public_id, "recruit_id": p.recruit_id, "recruiting": json.dumps(p.recruiting, sort_keys=True),
        "order_index": p.order_index, "condition_order": ";".join(p.condition_order),
        **design.group_of(p.condition_order), "status": p.status,
        "state": p.state, "step": p.step, "steps": p.steps, "test_run": int(p.test_run), "pilot": int(p.pilot),
        "excluded": int(p.excluded),
        "exclusion_reason": p.exclusion_reason, "created_at": iso_time(p.created_at),
        "finished_at": iso_time(p.finished_at),
        "practice_trials_finished": len({t.index for t in mine if t.kind == "practice"}),
        "main_trials_finished": len({t.index for t in mine if t.kind == "main"}),
        "cells": len(used.get(p.id, {})),
        "complete": int(not flagged(p) and not _missing_cells(p, trials, used, design)),
    }


def excluded_row(p: StoredParticipant, trials: Sequence[StoredTrial], used: Used,
                 design: ExportDesign) -> dict[str, Any] | None:
    """The participant's excluded.csv row, or ``None`` when they are in the complete-case analysis."""
    if flagged(p):
        reasons = (["test run"] if p.test_run else []) + (
            [f"excluded by the experimenter: {p.exclusion_reason or 'no reason given'}"] if p.excluded else [])
        return {"participant": p.public_id, "category": "test_run" if p.test_run else "excluded",
                "reason": "; ".join(reasons), "in_cells": 0}
    missing = _missing_cells(p, trials, used, design)
    if not missing:
        return None
    invalid = any(f" {INVALID_MARK}: " in m for m in missing)
    return {"participant": p.public_id, "category": _category(missing) if invalid else "incomplete",
            "reason": "; ".join(missing),
            "in_cells": int(bool(used.get(p.id)))}


def _category(missing: Sequence[str]) -> str:
    """``low_engagement`` when every invalid missing cell is a low-engagement trial, else ``invalid``."""
    marked = [m for m in missing if f" {INVALID_MARK}: " in m]
    return "low_engagement" if all(f" {INVALID_MARK}: {LOW_ENGAGEMENT}" in m for m in marked) else "invalid"


def _missing_cells(p: StoredParticipant, trials: Sequence[StoredTrial], used: Used, design: ExportDesign) -> list[str]:
    """``missing cell robot=…, kitchen=… (why)`` for each condition without a cell."""
    present = {design.cell_of(t.robot, t.kitchen, t.view, t.fov_angle) for t in used.get(p.id, {}).values()}
    out = []
    for cell in design.expected_cells(p.condition_order):
        if cell not in present:
            label = cell_label(design.fields, cell)
            out.append(f"missing cell {label} ({_why_missing(p, trials, '@'.join(cell))})")
    return out


def _why_missing(p: StoredParticipant, trials: Sequence[StoredTrial], condition: str) -> str:
    if condition not in p.condition_order:
        return "not in the participant's condition order"
    index = p.condition_order.index(condition)
    attempts = [t for t in trials if t.participant_id == p.id and t.kind == "main" and t.index == index]
    if not attempts:
        return f"main trial {index + 1} not played; participant {p.status}"
    last = max(attempts, key=lambda t: t.attempt)
    if last.status == "finished" and last.invalid:
        return f"main trial {index + 1} {INVALID_MARK}: {last.invalid_why}"
    if last.status == "running":
        return f"main trial {index + 1} still running"
    return f"main trial {index + 1} {last.status} ({last.end_reason or 'no reason'})"
