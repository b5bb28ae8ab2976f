"""Per-trial measures from the stored ticks and events (docs/domain.md §6, paper §VII).

With n stored ticks t = 1..n of one trial:

* the reference's KB gap (the paper's measure as its code computes it, docs/domain.md §6): d_t = Σ_c d_t,c, the
  per-component gap of tick t (``ticks.kb_diff``: grill, board, sink, robot's held object, as
  ``planner.summary.info_diff`` computes it from the reference's state info of the KB and of the world);
  ``kb_diff_freq`` = 100 · #{t : d_t > 0} / n; ``kb_diff_avg`` = Σ_t d_t / #{t : d_t > 0} (empty when no tick
  has a gap); ``kb_diff_mean`` = (1/n) Σ_t d_t.
* ``kb_gap_mean`` = (1/n) Σ_t gap_t, where gap_t (``ticks.kb_gap_total``) is the number of components
  (grill, board, sink, robot's held object) on which the participant's modelled KB differs from the world;
  ``kb_gap_ticks_pct`` = 100 · #{t : gap_t > 0} / n; ``kb_gap_<component>_pct`` = 100 · #{t : component
  differs} / n (a component's mean gap per tick is this divided by 100).
* ``interrupts`` = the participant's accepted interrupt actions (``events.kind = 'interrupt'``: up, down,
  left, right, stay, interact, stop); ``selections`` = subtask choices (``select_subtask``);
  ``interrupts_per_selection`` = 100 · interrupts / (interrupts + selections), empty when both are 0.
* ``ticks`` = world steps played (the trial row's count; the horizon when not finished), ``finished`` = 1
  when every order was delivered, ``delivered``, ``score``.
* ``robot_in_fov_pct`` = 100 · #{t : the robot's cell is in the participant's FOV after step t} / n.
* ``subtask_switches``, ``redundant_actions``, ``human_prep_pct``, ``human_plating_pct``, ``collisions``:
  see :mod:`analysis.measures.work`.
* robot timing: ``decision_ms_mean`` and ``decision_ms_p95`` over the ticks with a decision time (request
  to answer as the game loop saw it, late answers included), ``lateness_ms_mean`` and ``lateness_ms_p99``
  (actual start of a step − its scheduled start), ``deadline_misses`` = ticks where the robot's decision
  missed its deadline (the robot stayed). Percentiles use linear interpolation (numpy's default).

A trial without stored ticks has empty (NaN) tick-based measures.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from analysis.measures.work import redundant_action_flags, subtask_switch_flags, work_shares
from analysis.source.store_reader import StoredEvent, StoredTick, StoredTrial
from planner.summary import GAP_COMPONENTS, kb_diff_trial

TRIAL_MEASURES: tuple[str, ...] = (
    "ticks", "finished", "delivered", "score",
    "kb_diff_freq", "kb_diff_avg", "kb_diff_mean",
    "kb_gap_mean", "kb_gap_ticks_pct", *(f"kb_gap_{c}_pct" for c in GAP_COMPONENTS),
    "interrupts", "selections", "interrupts_per_selection",
    "robot_in_fov_pct", "subtask_switches", "redundant_actions", "human_prep_pct", "human_plating_pct",
    "collisions",
    "decision_ms_mean", "decision_ms_p95", "lateness_ms_mean", "lateness_ms_p99", "deadline_misses",
)
"""The measure columns of ``trials.csv`` and ``cells.csv``, in order."""

CONDUCT_COUNTS: tuple[str, ...] = ("disconnects", "blurs", "idle_events", "errors", "stall_hints")
"""Counts of participant-conduct events per trial (for exclusion rules), and of the stall hints the participant
was given (``server.game.stall_hint``), in ``trials.csv`` only."""

_CONDUCT_KIND = {"disconnects": "disconnect", "blurs": "blur", "idle_events": "idle", "errors": "error",
                 "stall_hints": "stall_hint"}
NAN = float("nan")


def trial_measures(trial: StoredTrial, ticks: Sequence[StoredTick], events: Sequence[StoredEvent],
                   ) -> dict[str, Any]:
    """Every measure of ``TRIAL_MEASURES`` and ``CONDUCT_COUNTS`` for one trial attempt."""
    out: dict[str, Any] = {
        "ticks": trial.ticks if trial.ticks else (ticks[-1].tick if ticks else 0),
        "finished": int(trial.status == "finished" and trial.end_reason == "delivered"),
        "delivered": trial.delivered,
        "score": trial.score,
    }
    out.update(kb_diff_measures(ticks))
    out.update(kb_gap_measures(ticks))
    out.update(input_measures(events))
    out["robot_in_fov_pct"] = _pct([t.robot_in_fov for t in ticks])
    out["subtask_switches"] = sum(subtask_switch_flags([t.subtask for t in ticks], [t.controller for t in ticks]))
    out["redundant_actions"] = sum(redundant_action_flags(trial.initial_state, [t.world_state for t in ticks]))
    out.update(work_shares([t.world_events for t in ticks]))
    out.update(timing_measures(ticks))
    for name, kind in _CONDUCT_KIND.items():
        out[name] = sum(1 for e in events if e.kind == kind)
    return out


def kb_diff_measures(ticks: Sequence[StoredTick]) -> dict[str, float]:
    """``kb_diff_freq``, ``kb_diff_avg`` and ``kb_diff_mean`` (the reference's KB gap; module docstring)."""
    if not ticks:
        return {"kb_diff_freq": NAN, "kb_diff_avg": NAN, "kb_diff_mean": NAN}
    freq, avg, mean = kb_diff_trial([t.kb_diff or {} for t in ticks])
    return {"kb_diff_freq": freq, "kb_diff_avg": NAN if avg is None else avg, "kb_diff_mean": mean}


def kb_gap_measures(ticks: Sequence[StoredTick]) -> dict[str, float]:
    """``kb_gap_mean``, ``kb_gap_ticks_pct`` and ``kb_gap_<component>_pct``."""
    totals = [t.kb_gap_total for t in ticks]
    out = {"kb_gap_mean": float(np.mean(totals)) if totals else NAN,
           "kb_gap_ticks_pct": _pct([v > 0 for v in totals])}
    for component in GAP_COMPONENTS:
        out[f"kb_gap_{component}_pct"] = _pct([bool(t.kb_gap.get(component, 0)) for t in ticks])
    return out


def input_measures(events: Sequence[StoredEvent]) -> dict[str, float | int]:
    """``interrupts``, ``selections`` and ``interrupts_per_selection`` (docs/domain.md §6)."""
    interrupts = sum(1 for e in events if e.kind == "interrupt")
    selections = sum(1 for e in events if e.kind == "select_subtask")
    both = interrupts + selections
    return {"interrupts": interrupts, "selections": selections,
            "interrupts_per_selection": 100.0 * interrupts / both if both else NAN}


def timing_measures(ticks: Sequence[StoredTick]) -> dict[str, float | int]:
    """Robot decision time (mean, p95), tick lateness (mean, p99) and deadline misses."""
    decisions = [t.decision_ms for t in ticks if t.decision_ms is not None and math.isfinite(t.decision_ms)]
    lateness = [t.lateness_ms for t in ticks]
    return {
        "decision_ms_mean": float(np.mean(decisions)) if decisions else NAN,
        "decision_ms_p95": float(np.percentile(decisions, 95)) if decisions else NAN,
        "lateness_ms_mean": float(np.mean(lateness)) if lateness else NAN,
        "lateness_ms_p99": float(np.percentile(lateness, 99)) if lateness else NAN,
        "deadline_misses": sum(1 for t in ticks if t.robot_missed),
    }


def _pct(flags: Sequence[bool]) -> float:
    return 100.0 * sum(flags) / len(flags) if flags else NAN
