"""A stored trial as frames for the replay viewer: tick 0 (the trial's initial state) and every stored tick,
each the whole world with the participant's field of view (:mod:`server.admin.scenes`), the modelled KB's
kitchen, and what was recorded at that tick (actions, subtask, KB-gap components, robot in view, lateness,
the robot's decision with its belief over the participant's subtask).

The field of view is recomputed from the stored human pose with the trial's stored ``fov_angle`` (the study's
current ``world.fov_angle`` for trials stored before it was recorded);
``config_changed`` says when the study file now differs from the one the trial was played with.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from planner.kb import KnowledgeBase, initial_kb
from planner.layout import Layout
from planner.rules import Rules
from planner.state import WorldState
from planner.summary import gap_components, summarize
from server.admin.scenes import frame, grid, kb_frame
from server.errors import ApiError
from store.tables import TickRow, TrialRow
from study_config.catalog import LoadedStudy

RECORDED = ("human_action", "robot_action", "action_source", "subtask", "kb_gap", "kb_gap_total", "kb_summary",
            "world_summary", "robot_in_fov", "lateness_ms", "decision_ms", "robot_missed")


def replay(loaded: LoadedStudy | None, row: TrialRow, ticks: Sequence[TickRow], *, start: int,
           limit: int) -> dict[str, Any]:
    """Frames from tick ``start`` (0 = the initial state) for at most ``limit`` stored ticks; ``next_start`` is
    where the next page begins, or ``None`` after the last stored tick."""
    if loaded is None or row.kitchen not in loaded.layouts:
        raise ApiError(410, "study_gone", "the study or kitchen of this trial is no longer served, so it cannot "
                                          "be drawn; its ticks are still in GET /api/admin/trials/{id}")
    layout, rules, angle = loaded.layout(row.kitchen), loaded.rules, loaded.study.trial_angle(row.fov_angle)
    frames: list[dict[str, Any]] = []
    if start == 0:
        frames.append(_initial(layout, WorldState.from_dict(row.initial_state), rules, angle))
    for tick in ticks:
        world = WorldState.from_dict(tick.world_state)
        frames.append({**frame(layout, world, rules, angle),
                       "kb": kb_frame(layout, KnowledgeBase.from_dict(tick.kb_state), rules),
                       **{name: getattr(tick, name) for name in RECORDED}, "decision": tick.robot_info})
    return {
        "grid": grid(layout),
        "fov_angle": angle,
        "tick_rate_hz": loaded.study.timing.tick_rate_hz,
        "horizon": rules.horizon,
        "config_changed": row.config_hash != loaded.study.config_hash(),
        "frames": frames,
        "next_start": ticks[-1].tick + 1 if len(ticks) >= limit else None,
    }


def _initial(layout: Layout, world: WorldState, rules: Rules, angle: float) -> dict[str, Any]:
    """Tick 0: the initial state, the KB the participant starts with (the setup, known to both), no actions."""
    kb = initial_kb(world)
    first = frame(layout, world, rules, angle)
    kb_summary, world_summary = summarize(kb, rules), summarize(world, rules)
    gap = gap_components(kb_summary, world_summary)
    return {**first, "kb": kb_frame(layout, kb, rules), **dict.fromkeys(RECORDED),
            "kb_summary": kb_summary.to_dict(), "world_summary": world_summary.to_dict(), "kb_gap": gap,
            "kb_gap_total": sum(gap.values()), "robot_in_fov": list(world.robot.pos) in first["fov"],
            "decision": None}
