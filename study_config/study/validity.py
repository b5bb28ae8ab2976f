"""When a trial counts as data: the study's ``validity`` section (docs/operations.md, "Robot health" and
"Engagement").

Two rules mark a main trial as not analysable: the robot's health (decisions past their deadline, or a robot that
undoes its own last interaction: ``server.game.health``) and the participant's engagement
(``server.flow.engagement``: a round played without taking part). A participant with more abandoned or
low-engagement main rounds than ``max_invalid_rounds`` gets the screen-out outcome instead of the completion code
(``server.flow.standing``).

:func:`round_status` is the one rule for what an attempt at a trial is worth as data, shared by the server
(whether a participant still counts toward their condition order, and whether they took part:
``server.flow.standing``) and the analysis (the ``trial_status`` column: ``analysis.measures.participation``).
"""

from __future__ import annotations

from typing import Literal

from pydantic import Field

from study_config.study.base import StudyModel

DEFAULT_MAX_MISSED_DECISIONS_PCT = 5.0
"""A trial whose robot missed more than this share of its decision deadlines is invalid."""
DEFAULT_MAX_IDLE_PCT = 95.0
"""A main trial in which the cook had nothing to do for more than this share of its tick periods is
low-engagement. Chosen from the real-time pilots of docs/pilot.md §4 (28 simulated participants per clock who
think 0.5–3 s per choice): their highest per-trial idle share was 70.8 % (``fixed_rate``) and 86.8 %
(``wait_for_participant``); on their median round, 95 % takes about 21 s of idleness per choice (90 % only
about 10 s, within reach of a slow but real player), while a participant who never acts has 100 %."""


DEFAULT_MIN_TASK_STEP_PCT = 10.0
"""A main trial in which the participant made less than this share of the team's task steps is low-engagement.
Chosen from the pilots of docs/protocol.md, "Taking part" (paper's clock, 2026-12-07): the 28 human-like simulated
participants made 41.9 % to 86.2 % per round (112 rounds), the scripts that held, tapped or pressed one key 0 %."""
DEFAULT_MAX_REFUSED_TASK_PCT = 25.0
"""Above this share of refused task choices over the main rounds so far (at least five refused) a main trial is
low-engagement. From the same pilots: the human-like participants pooled at most 13.2 %, the scripts choosing a
random enabled task every 8 s or 3 s at least 35.6 % (a single human-like round reached 27.3 %: hence pooled)."""


RoundStatus = Literal["running", "abandoned", "low_engagement", "robot_invalid", "finished"]
RUNNING: RoundStatus = "running"
ABANDONED: RoundStatus = "abandoned"
LOW_ENGAGEMENT: RoundStatus = "low_engagement"
ROBOT_INVALID: RoundStatus = "robot_invalid"
FINISHED: RoundStatus = "finished"


def round_status(status: str, engagement_reason: str | None, invalid_reason: str | None) -> RoundStatus:
    """What an attempt at a trial is worth as data, from its stored ``status`` (running / finished / abandoned)
    and the server's marks: ``running``, ``abandoned`` (the participant did not return within the grace window),
    ``robot_invalid`` (finished, the robot's decisions missed their deadlines too often), ``low_engagement``
    (finished, but the participant did not take part) or ``finished`` (it can be an analysable cell). The robot's
    failure comes first: a round the robot broke says nothing about the participant (a stalled robot standing in
    the way refuses their tasks), so it never counts against them, whatever else it was marked."""
    if status == RUNNING:
        return RUNNING
    if status == ABANDONED:
        return ABANDONED
    if status != FINISHED:
        raise ValueError(f"unknown trial status {status!r}")
    if invalid_reason:
        return ROBOT_INVALID
    if engagement_reason:
        return LOW_ENGAGEMENT
    return FINISHED


class Validity(StudyModel):
    """Rules that mark a trial invalid as it happens; invalid trials are left out of the analysis by default."""

    max_missed_decisions_pct: float = Field(default=DEFAULT_MAX_MISSED_DECISIONS_PCT, ge=0, le=100)
    """The robot stood still for a missed decision; past this share of the trial's decisions (in %) the trial
    did not test the robot the condition names, and is marked invalid with the share as the reason."""
    max_robot_flickers: int = Field(default=0, ge=0)
    """The robot undid its own last interaction (put an item down and picked it up again, or the reverse) with
    nothing else changed more often than this (``planner/flicker.py``; the planners never choose to): the trial did
    not test the robot the condition names, and is marked invalid with the count as the reason."""
    min_participant_actions: int = Field(default=1, ge=0)
    """A main trial with fewer of the participant's actions (task choices plus interrupts) is
    ``low_engagement``: the robot played it alone."""
    min_task_step_pct: float = Field(default=DEFAULT_MIN_TASK_STEP_PCT, ge=0, le=100)
    """A main trial in which the participant made less than this share of the team's task steps (interactions
    that changed the world), in %, is ``low_engagement``: the robot did the work while they held or tapped a key,
    or chose tasks that got nowhere (0 turns the rule off)."""
    max_refused_task_pct: float = Field(default=DEFAULT_MAX_REFUSED_TASK_PCT, ge=0, le=100)
    """A main trial in which more than this share of the participant's task choices were refused (could not work),
    once at least five were, is ``low_engagement``: tasks chosen without looking (100 turns the rule off)."""
    max_idle_pct: float = Field(default=DEFAULT_MAX_IDLE_PCT, ge=0, le=100)
    """A main trial whose cook had nothing to do (no task, no key waiting) for more than this share of its tick
    periods (``idle_pct``; in ``wait_for_participant`` the time the world waited counts at the tick rate) is
    ``low_engagement``."""
    max_invalid_rounds: int = Field(default=0, ge=0)
    """Main rounds that may be abandoned (grace window expired) or low-engagement before the participant gets
    the screen-out outcome instead of the completion code (0: the first one ends the study)."""
