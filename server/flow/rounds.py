"""Rounds seen from the participant's pages: what happens to a round they left, and what the pages say about
their current and previous round (in progress elsewhere, ended while they were away)."""

from __future__ import annotations

from dataclasses import dataclass
from datetime import datetime
from typing import Literal

from sqlalchemy.orm import Session

from server.flow.plan import Step
from server.flow.progress import Progress
from store import trials
from store.lease import away_seconds
from store.tables import TrialRow
from study_config.study.sections import Reconnect

Return = Literal["resume", "restart", "abandon"]
RoundStatus = Literal["new", "in_progress", "ended_away", "restart"]


def on_return(away_s: float, reconnect: Reconnect) -> Return:
    """What a running round becomes when its participant connects after ``away_s`` seconds away
    (``store.lease.away_seconds``: time away while a server was up, restarted at a server start): within the study's
    grace window it resumes; later, what ``reconnect.after_grace`` says."""
    if away_s <= reconnect.grace_seconds:
        return "resume"
    return reconnect.after_grace


@dataclass(frozen=True, slots=True)
class RoundFacts:
    """What the session view says about rounds: the current round's status, and whether the round before the
    current step ended while the participant was away."""

    current: RoundStatus | None
    previous_ended_away: bool


def round_facts(session: Session, participant_id: int, progress: Progress, now: datetime,
                reconnect: Reconnect, connected: frozenset[int] = frozenset()) -> RoundFacts:
    """``connected``: the trials a participant is connected to in this process. Such a round is in progress
    whatever the store says. A round connected in another process is judged by its lease (``store.lease``), which
    that process renews at every store flush: connected there, it is in progress."""
    step = progress.current
    current: RoundStatus | None = None
    if step.kind == "trial" and step.trial_kind is not None and step.index is not None and not progress.screened_out:
        row = trials.latest_attempt(session, participant_id, step.trial_kind, step.index)
        current = "in_progress" if row is not None and row.id in connected else _status(row, now, reconnect)
    before = _previous_trial(progress)
    away = False
    if before is not None and before.trial_kind is not None and before.index is not None:
        row = trials.latest_attempt(session, participant_id, before.trial_kind, before.index)
        away = row is not None and row.status == trials.ABANDONED and row.end_reason == "grace_expired"
    return RoundFacts(current, away)


_STATUS_ON_RETURN: dict[Return, RoundStatus] = {"resume": "in_progress", "restart": "restart",
                                                "abandon": "ended_away"}


def _status(row: TrialRow | None, now: datetime, reconnect: Reconnect) -> RoundStatus:
    if row is None or row.status != trials.RUNNING:
        return "new"
    return _STATUS_ON_RETURN[on_return(away_seconds(row, now), reconnect)]


def _previous_trial(progress: Progress) -> Step | None:
    """The trial step right before the current step, counting only questionnaires in between."""
    for step in reversed(progress.plan[: progress.step]):
        if step.kind == "trial":
            return step
        if step.kind != "questionnaire":
            return None
    return None
