"""What a pilot's participants did in their main rounds, per robot × kitchen (docs/pilot.md, "Who did the work"):
read through the admin API after the run (``GET /api/admin/trials`` and ``/participants``), so it works for a started
server and for one given with ``--url`` alike.

Per cell, over the ended main trials of the run's participants:

- ``dishes``: the participant's dishes / the team's, and the share;
- ``task_steps``: the participant's share of the team's task steps (interactions that changed the world);
- ``refused``: the participant's refused steps per trial;
- ``stand_ticks``: world steps in which the participant had no executable action (the paper's clock's goal: 0);
- ``think_s``: wall-clock think time per trial, and per task choice;
- ``excluded``: trials marked low-engagement (the participant did not take part) or robot-invalid.

Trials stored before these measures existed have no value for them and are left out of that column's sums.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import httpx


@dataclass(frozen=True, slots=True)
class CellReport:
    robot: str
    kitchen: str
    trials: int
    dishes_participant: int
    dishes_team: int
    task_steps_participant: int
    task_steps_team: int
    refused_steps: int
    stand_ticks: int
    think_seconds: float
    selections: int
    low_engagement: int
    robot_invalid: int

    @property
    def dish_share(self) -> float | None:
        return 100.0 * self.dishes_participant / self.dishes_team if self.dishes_team else None

    @property
    def task_step_share(self) -> float | None:
        return 100.0 * self.task_steps_participant / self.task_steps_team if self.task_steps_team else None


def _int(value: Any) -> int:
    return int(value) if value is not None else 0


def cell_reports(trials: Iterable[Mapping[str, Any]], recruit_ids: Iterable[str] | None = None) -> list[CellReport]:
    """The table's rows from the admin API's trials (``recruit_ids``: only these participants' trials), in robot
    then kitchen order as first met."""
    keep = None if recruit_ids is None else {r.strip().lower() for r in recruit_ids}
    cells: dict[tuple[str, str], list[Mapping[str, Any]]] = {}
    for t in trials:
        if t["kind"] != "main" or t["status"] == "running" or (keep is not None and t.get("recruit_id") not in keep):
            continue
        cells.setdefault((t["robot"], t["kitchen"]), []).append(t)
    rows = []
    for (robot, kitchen), group in cells.items():
        rows.append(CellReport(
            robot=robot, kitchen=kitchen, trials=len(group),
            dishes_participant=sum(_int(t["delivered_by_participant"]) for t in group),
            dishes_team=sum(_int(t["delivered_by_participant"]) + _int(t["delivered_by_robot"]) for t in group),
            task_steps_participant=sum(_int(t.get("task_steps")) for t in group),
            task_steps_team=sum(_int(t.get("task_steps")) + _int(t.get("robot_task_steps")) for t in group),
            refused_steps=sum(_int(t["refused_steps"]) for t in group),
            stand_ticks=sum(_int(t.get("stand_ticks")) for t in group),
            think_seconds=sum(float(t.get("think_seconds") or 0.0) for t in group),
            selections=sum(_int(t["selections"]) for t in group),
            low_engagement=sum(bool(t["low_engagement"]) for t in group),
            robot_invalid=sum(bool(t["invalid"]) and not t["low_engagement"] for t in group)))
    return sorted(rows, key=lambda r: (r.robot, r.kitchen))


def _pct(value: float | None) -> str:
    return "–" if value is None else f"{value:.1f} %"


def markdown(rows: Sequence[CellReport], screened_out: Mapping[str, int] | None = None) -> str:
    """The table as Markdown (docs/pilot.md), with the screened-out participants by reason below it."""
    lines = ["| robot × kitchen | trials | participant's dishes | participant's task steps | refused steps / trial "
             "| ticks with no executable action | think time / trial (/ choice) | excluded trials |",
             "|---|---|---|---|---|---|---|---|"]
    for r in [*rows, _total(rows)] if rows else []:
        per_choice = f"{r.think_seconds / r.selections:.1f} s" if r.selections else "no choice"
        excluded = f"{r.low_engagement} low-engagement, {r.robot_invalid} robot-invalid"
        lines.append(
            f"| {r.robot} × {r.kitchen} | {r.trials} "
            f"| {r.dishes_participant} of {r.dishes_team} ({_pct(r.dish_share)}) "
            f"| {r.task_steps_participant} of {r.task_steps_team} ({_pct(r.task_step_share)}) "
            f"| {r.refused_steps / r.trials:.2f} | {r.stand_ticks} "
            f"| {r.think_seconds / r.trials:.1f} s ({per_choice}) | {excluded} |")
    if screened_out is not None:
        reasons = ", ".join(f"{n} {reason.replace('_', ' ')}" for reason, n in sorted(screened_out.items()))
        lines.append("")
        lines.append(f"Participants screened out: {reasons or 'none'}.")
    return "\n".join(lines)


def _total(rows: Sequence[CellReport]) -> CellReport:
    def total(name: str) -> Any:
        return sum(getattr(r, name) for r in rows)

    return CellReport("all", "all", **{f: total(f) for f in CellReport.__dataclass_fields__
                                       if f not in ("robot", "kitchen")})


def fetch(base_url: str, admin_token: str, study_id: str, recruit_ids: Sequence[str],
          verify: Any = True) -> tuple[list[CellReport], dict[str, int]]:
    """The run's table and its screened-out participants by reason, read through the admin API."""
    headers = {"Authorization": f"Bearer {admin_token}"}
    keep = {r.strip().lower() for r in recruit_ids}
    with httpx.Client(base_url=base_url, headers=headers, timeout=60, verify=verify) as http:
        trials = http.get("/api/admin/trials", params={"study_id": study_id}).raise_for_status().json()
        people = http.get("/api/admin/participants", params={"study_id": study_id}).raise_for_status().json()
    screened: dict[str, int] = {}
    for p in people:
        recruit = str(next(iter(p["recruiting"].values()), "")).strip().lower() if p["recruiting"] else ""
        if recruit in keep and p["status"] == "screened_out":
            reason = p["screen_out_reason"] or "unknown"
            screened[reason] = screened.get(reason, 0) + 1
    return cell_reports(trials, recruit_ids), screened
