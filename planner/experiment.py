"""The paper's simulation experiment (§VI): robots × kitchens × seeds with the simulated FOV-limited human.

One trial per (kitchen, robot, seed); the human's random stream depends only on the seed, so the robots
are compared on paired trials. :func:`summarize_trials` gives the paper-style table: mean ± sd ticks per
robot per kitchen and overall, and the paired difference of the FOV-aware robot against the baseline
(mean % change of ticks, paired t-test p and Wilcoxon signed-rank p); then the paper's two robot behaviours per
kitchen and robot (:mod:`planner.behaviours`): does the FOV-aware robot show itself in this kitchen?

Any installed robot plays (:mod:`planner.robot_catalog`: the shipped planners and plug-ins), guarded
(:class:`planner.robot_guard.GuardedRobot`): a decision that raised, was illegal or hung makes the robot stay
that tick and flags the trial (``robot_faults``, ``robot_fault``; :func:`flagged_lines`).
"""

from __future__ import annotations

import statistics
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy import stats

from planner import robot_catalog
from planner.decision import Decision, Robot
from planner.layout import Layout
from planner.partner import Person as SimulatedPerson
from planner.perception import FOV_ANGLE, KB_DELAY
from planner.play import TrialResult, TrialSettings, run_trial
from planner.robot_api import Person
from planner.robot_catalog import RobotSetup
from planner.robot_guard import HANG_S, GuardedRobot
from planner.rules import Rules

COLUMNS = ("layout", "robot", "seed", "ticks", "finished", "reward", "kb_diff_freq", "kb_diff_avg", "kb_diff_mean",
           "kb_gap_mean", "kb_gap_ticks_pct",
           "robot_in_fov_pct", "decision_ms_p50", "decision_ms_p99", "holdings", "shown", "trips",
           "trip_share_sum", "robot_gap_pct", "gap_lag_pct", "gap_unseen_pct", "gap_stale_pct",
           "robot_place_cells", "robot_place_wrong_pct", "person_deliveries", "robot_deliveries", "person_steps",
           "robot_steps", "first_delivery", "robot_flickers", "robot_faults", "robot_fault")
GAP_PARTS = ("lag", "unseen", "stale")
"""The robot gap's parts (:func:`planner.behaviours.hands_gap`), % of ticks: they sum to ``robot_gap_pct``."""


@dataclass(frozen=True, slots=True)
class TrialSpec:
    """One simulated trial. ``robot`` names the robot in the results; ``planner`` is the installed robot that plays
    it (default: ``robot``) with ``settings`` (fields of its declared settings, checked by the study) changed: a
    study's own robot (its ``robot_variants``). ``human_angle`` and ``kb_delay`` are the study's person: what every
    robot is told of them and, unless ``person`` says otherwise, the simulated person
    (:class:`planner.partner.Person`: a person who differs from the robots' model). ``rules``: the kitchen's numbers
    (a study's ``world``)."""

    layout: Layout
    robot: str
    seed: int
    human_angle: float = FOV_ANGLE
    kb_delay: int = KB_DELAY
    planner: str | None = None
    settings: tuple[tuple[str, Any], ...] = ()
    rules: Rules = field(default_factory=Rules)
    person: SimulatedPerson | None = None
    hang_s: float = HANG_S
    """A decision running this long is stopped and the trial flagged (:mod:`planner.robot_guard`)."""

    @property
    def installed(self) -> str:
        """The installed robot that plays the trial."""
        return self.planner or self.robot

    def setup(self) -> RobotSetup:
        """What the robot is built with: the study's person's view and KB delay, and its settings."""
        return RobotSetup(Person(self.human_angle, self.kb_delay), self.settings)

    def simulated(self) -> SimulatedPerson:
        """The simulated person: ``person``, or the study's."""
        return self.person if self.person is not None else SimulatedPerson(self.human_angle, self.kb_delay)


class _Unbuilt:
    """A robot whose factory raised: its ``reset`` raises that again, so the guard flags the trial."""

    def __init__(self, exc: Exception) -> None:
        self.exc = exc

    def reset(self, *args: object) -> None:
        raise self.exc

    def decide(self, *args: object) -> Decision:
        raise self.exc


def run_spec(spec: TrialSpec) -> dict[str, object]:
    """One simulated trial as a row of ``trials.csv`` (importable by worker processes; the kitchen travels in
    the spec, so planner/ reads no files)."""
    layout, rules, person = spec.layout, spec.rules, spec.simulated()
    try:
        built: Robot = robot_catalog.build(spec.installed, layout, rules, spec.setup())
    except Exception as exc:  # flagged below, like a robot that fails later
        built = _Unbuilt(exc)
    robot = GuardedRobot(built, spec.hang_s)
    result = run_trial(layout, spec.seed, TrialSettings(angle=person.angle, kb_delay=person.delay, rules=rules),
                       robot=robot, human=person.model(layout, rules))
    times = np.array(result.decision_ms) if result.decision_ms else np.zeros(1)
    return {
        "layout": layout.name, "robot": spec.robot, "seed": spec.seed, "ticks": result.ticks,
        "finished": int(result.finished), "reward": result.score,
        "kb_diff_freq": round(result.kb_diff_freq, 2),
        "kb_diff_avg": "" if result.kb_diff_avg is None else round(result.kb_diff_avg, 4),
        "kb_diff_mean": round(result.kb_diff_mean, 4),
        "kb_gap_mean": round(result.kb_gap_mean, 4), "kb_gap_ticks_pct": round(result.kb_gap_ticks_pct, 2),
        "robot_in_fov_pct": round(result.robot_in_fov_pct, 2),
        "decision_ms_p50": round(float(np.percentile(times, 50)), 3),
        "decision_ms_p99": round(float(np.percentile(times, 99)), 3),
        **behaviour_columns(result), **work_columns(result),
        "robot_faults": robot.faults, "robot_fault": robot.first_fault or "",
    }


def work_columns(result: TrialResult) -> dict[str, object]:
    """Who delivered and who did the task steps (:mod:`planner.work_share`), and the robot's flickers."""
    work = result.work
    first = "human" if work.first.person else "robot" if work.first.robot else ""
    return {"person_deliveries": work.deliveries.person, "robot_deliveries": work.deliveries.robot,
            "person_steps": work.steps.person, "robot_steps": work.steps.robot, "first_delivery": first,
            "robot_flickers": result.flickers}


def behaviour_columns(result: TrialResult) -> dict[str, object]:
    """The columns of the paper's robot behaviours and the robot gap's parts of one trial, and where the person's KB
    places the robot (how many cells off, on average; % of ticks elsewhere)."""
    b, hands = result.behaviours, result.hands
    return {"holdings": b.holdings, "shown": b.shown, "trips": b.trips, "trip_share_sum": round(b.trip_share_sum, 4),
            "robot_gap_pct": round(result.gap_component_pct["robot_held"], 2),
            **{f"gap_{part}_pct": round(100.0 * getattr(hands, part) / max(hands.ticks, 1), 2) for part in GAP_PARTS},
            "robot_place_cells": round(result.robot_place_cells, 3),
            "robot_place_wrong_pct": round(result.robot_place_wrong_pct, 2)}


@dataclass(frozen=True, slots=True)
class PairedComparison:
    robot: str
    reference: str
    pairs: int
    mean_change_pct: float
    t_p: float
    wilcoxon_p: float


def paired_comparison(rows: list[dict[str, Any]], robot: str = "fov_aware",
                      reference: str = "baseline") -> PairedComparison | None:
    """Ticks of ``robot`` against ``reference`` on the same (kitchen, seed) trials."""
    by_key = {(r["layout"], r["seed"], r["robot"]): float(r["ticks"]) for r in rows}
    keys = sorted({(k, s) for k, s, rb in by_key if rb == robot and (k, s, reference) in by_key})
    if len(keys) < 2:
        return None
    a = np.array([by_key[(k, s, robot)] for k, s in keys])
    b = np.array([by_key[(k, s, reference)] for k, s in keys])
    change = 100.0 * (a.mean() - b.mean()) / b.mean()
    t_p = float(stats.ttest_rel(a, b).pvalue) if np.any(a != b) else 1.0
    w_p = float(stats.wilcoxon(a, b).pvalue) if np.any(a != b) else 1.0
    return PairedComparison(robot, reference, len(keys), float(change), t_p, w_p)


def summarize_trials(rows: list[dict[str, Any]]) -> str:
    """The paper-style table as text."""
    robots = sorted({str(r["robot"]) for r in rows}, key=lambda r: (r != "fov_aware", r))
    layouts = sorted({str(r["layout"]) for r in rows})
    head = f"{'kitchen':<10}" + "".join(f"{rb:>22}" for rb in robots)
    lines = ["ticks to finish (mean ± sd; unfinished trials count the horizon)", head, "-" * len(head)]
    for layout in layouts + ["overall"]:
        cells = []
        for rb in robots:
            ticks = [float(r["ticks"]) for r in rows
                     if r["robot"] == rb and (layout == "overall" or r["layout"] == layout)]
            unfinished = sum(1 for r in rows if r["robot"] == rb and not r["finished"]
                             and (layout == "overall" or r["layout"] == layout))
            sd = statistics.stdev(ticks) if len(ticks) > 1 else 0.0
            mark = f" ({unfinished} unf.)" if unfinished else ""
            cells.append(f"{statistics.mean(ticks):.1f} ± {sd:.1f}{mark}" if ticks else "-")
        lines.append(f"{layout:<10}" + "".join(f"{c:>22}" for c in cells))
    comparison = paired_comparison(rows)
    if comparison is not None:
        lines.append(f"fov_aware vs baseline over {comparison.pairs} paired trials: "
                     f"{comparison.mean_change_pct:+.1f}% ticks, paired t-test p = {comparison.t_p:.4g}, "
                     f"Wilcoxon p = {comparison.wilcoxon_p:.4g}")
    return "\n".join(lines + behaviour_lines(rows, robots, layouts) + flagged_lines(rows))


def flagged_lines(rows: list[dict[str, Any]]) -> list[str]:
    """The trials whose robot failed (raised, answered an illegal decision or hung), one line each; none when no
    robot failed (or for rows written before the columns existed)."""
    flagged = [r for r in rows if int(r.get("robot_faults") or 0) > 0]
    if not flagged:
        return []
    return ["", f"{len(flagged)} trial(s) flagged: the robot failed (it stood still at each failed decision):"] + [
        f"  {r['robot']} on {r['layout']} seed {r['seed']}: {r['robot_faults']} failed decision(s); first at "
        f"{r['robot_fault']}" for r in flagged]


def behaviour_lines(rows: list[dict[str, Any]], robots: list[str], layouts: list[str]) -> list[str]:
    """The paper's behaviours per kitchen and robot, pooled over seeds; none for rows written without them."""
    if not rows or any(r.get("holdings") in (None, "") for r in rows):
        return []
    width = max(14, *(len(rb) + 2 for rb in robots))
    lines = ["", "the paper's robot behaviours (docs/domain.md §6, \"Behaviours\"), pooled over seeds:",
             "  b1 = share of pickups shown kb_delay ticks in a row; b2 = mean share of a dish trip in the person's "
             "view;",
             "  robot gap = % of ticks the person's KB is wrong about what the robot holds = lag + unseen + stale;",
             "  robot off = how many cells from where it is the person's KB places the robot, on average",
             f"{'kitchen':<10}{'robot':<{width}}{'b1 shown':>14}{'b2 trip share':>20}{'robot off':>11}   robot gap %"]
    for layout in layouts:
        for rb in robots:
            mine = [r for r in rows if r["robot"] == rb and r["layout"] == layout]
            if not mine:
                continue
            holdings, trips = sum(int(r["holdings"]) for r in mine), sum(int(r["trips"]) for r in mine)
            b1 = f"{sum(int(r['shown']) for r in mine) / holdings:.2f} ({holdings})" if holdings else "-"
            b2 = (f"{sum(float(r['trip_share_sum']) for r in mine) / trips:.2f} ({trips} trips)"
                  if trips else "-")
            parts = " + ".join(f"{statistics.mean(float(r[f'gap_{p}_pct']) for r in mine):.1f}" for p in GAP_PARTS)
            gap = statistics.mean(float(r["robot_gap_pct"]) for r in mine)
            off = statistics.mean(float(r["robot_place_cells"]) for r in mine)
            lines.append(f"{layout:<10}{rb:<{width}}{b1:>14}{b2:>20}{off:>11.2f}   {gap:.1f} = {parts}")
    return lines
