"""Whether a participant still counts, and whether they took part: the one home of both rules
(docs/operations.md, "Engagement").

**Counting toward a condition order** (:mod:`store.assignment`): a participant counts only while every
main round of theirs can still become an analysable cell. They stop counting (``participants.uncounted_reason``,
kept once set) when a main round ends abandoned (grace window expired), ``low_engagement``
(:mod:`server.flow.engagement`) or invalid for the robot's health (``server.game.health``); and while their
device check was refused (cleared when a later check on an accepted device passes). The next participant then
gets their order.

**Taking part**: a participant with more abandoned or low-engagement main rounds than the study's
``validity.max_invalid_rounds`` is screened out as that round ends (reason ``abandoned_rounds`` if any round
was abandoned, else ``low_engagement``): they get the study's screen-out code and redirect, never the completion
code. A robot-invalid round is not the participant's doing and never screens them out.
"""

from __future__ import annotations

import logging
from collections.abc import Sequence

from sqlalchemy import select
from sqlalchemy.orm import Session

from store import trials
from store.tables import ParticipantRow, TrialRow
from study_config.study.validity import ABANDONED, LOW_ENGAGEMENT, ROBOT_INVALID, RoundStatus, Validity, round_status

log = logging.getLogger(__name__)

DEVICE_REFUSED = "device_refused"
ABANDONED_ROUNDS = "abandoned_rounds"
LOW_ENGAGEMENT_ROUNDS = "low_engagement"


def latest_main_trials(session: Session, participant_id: int) -> list[TrialRow]:
    """The latest ended attempt at each main trial of the participant, by index."""
    rows = session.scalars(select(TrialRow).where(TrialRow.participant_id == participant_id, TrialRow.kind == "main",
                                                  TrialRow.status != trials.RUNNING)
                           .order_by(TrialRow.index, TrialRow.attempt))
    latest: dict[int, TrialRow] = {}
    for row in rows:
        latest[row.index] = row
    return [latest[i] for i in sorted(latest)]


def earlier_choices(session: Session, participant_id: int, index: int) -> tuple[int, int]:
    """The task choices and refused steps of the participant's main rounds before round ``index`` (their latest
    attempts), for the engagement rule that pools them (``server.flow.engagement``)."""
    rows = [r for r in latest_main_trials(session, participant_id) if r.index < index]
    return sum(r.selections or 0 for r in rows), sum(r.refused_steps or 0 for r in rows)


def _status(row: TrialRow) -> RoundStatus:
    return round_status(row.status, row.engagement_reason, row.invalid_reason)


def round_problem(row: TrialRow) -> str | None:
    """Why an ended main trial cannot become an analysable cell (``study_config.study.validity.round_status``),
    or ``None``."""
    status = _status(row)
    if status == ABANDONED:
        return f"main round {row.index + 1} abandoned ({row.end_reason})"
    if status == LOW_ENGAGEMENT:
        return f"main round {row.index + 1} {row.engagement_reason}"
    if status == ROBOT_INVALID:
        return f"main round {row.index + 1} robot-invalid: {row.invalid_reason}"
    return None


def not_taking_part(rounds: Sequence[TrialRow], validity: Validity) -> str | None:
    """The screen-out reason when the participant's abandoned and low-engagement rounds exceed
    ``validity.max_invalid_rounds``, else ``None``."""
    statuses = [_status(r) for r in rounds]
    abandoned, low = statuses.count(ABANDONED), statuses.count(LOW_ENGAGEMENT)
    if abandoned + low <= validity.max_invalid_rounds:
        return None
    return ABANDONED_ROUNDS if abandoned else LOW_ENGAGEMENT_ROUNDS


def review_rounds(session: Session, row: ParticipantRow, validity: Validity) -> str | None:
    """After a main trial ended: stop counting the participant if a round cannot become a cell; answer the
    screen-out reason if they did not take part (the caller moves them)."""
    rounds = latest_main_trials(session, row.id)
    problems = [p for p in (round_problem(r) for r in rounds) if p is not None]
    if problems and (row.uncounted_reason is None or row.uncounted_reason.startswith(DEVICE_REFUSED)):
        row.uncounted_reason = problems[0][:200]
        log.info("participant %s no longer counts toward their condition order: %s", row.public_id,
                 row.uncounted_reason)
    return not_taking_part(rounds, validity)


def review_device(row: ParticipantRow, problems: Sequence[str]) -> None:
    """After a device check: a refused device stops the participant counting; an accepted one restores a
    participant who stopped counting only for their device."""
    if problems:
        if row.uncounted_reason is None:
            row.uncounted_reason = f"{DEVICE_REFUSED}: {'; '.join(problems)}"[:200]
    elif row.uncounted_reason is not None and row.uncounted_reason.startswith(DEVICE_REFUSED):
        row.uncounted_reason = None
