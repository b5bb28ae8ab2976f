"""Participant rows: created at join (with their assignment), found by token hash, advanced by the flow.

Tokens are never stored: only their SHA-256. Progress updates are optimistic (``WHERE step = :old``), so
two concurrent requests for the same step cannot both advance it.
"""

from __future__ import annotations

import hashlib
from datetime import datetime
from typing import Any

from sqlalchemy import select, update
from sqlalchemy.orm import Session

from store.tables import AssignmentRow, ParticipantRow
from store.types import utcnow


def hash_token(token: str) -> str:
    return hashlib.sha256(token.encode("utf-8")).hexdigest()


def by_token(session: Session, token: str) -> ParticipantRow | None:
    return session.scalar(select(ParticipantRow).where(ParticipantRow.token_hash == hash_token(token)))


def by_public_id(session: Session, public_id: str) -> ParticipantRow | None:
    return session.scalar(select(ParticipantRow).where(ParticipantRow.public_id == public_id))


def by_recruit_key(session: Session, study_id: str, key: str) -> ParticipantRow | None:
    """The participant of ``study_id`` whose recruiting id has the key ``key`` (``store.recruit_ids``)."""
    return session.scalar(select(ParticipantRow).where(ParticipantRow.study_id == study_id,
                                                       ParticipantRow.recruit_key == key))


def assignment_of(session: Session, participant_id: int) -> AssignmentRow | None:
    return session.scalar(select(AssignmentRow).where(AssignmentRow.participant_id == participant_id))


def create(session: Session, *, study_id: str, public_id: str, token: str, recruit_id: str | None,
           recruiting: dict[str, str], config_hash: str, plan: list[dict[str, Any]], state: str,
           test_run: bool, order_index: int, condition_order: list[str],
           pilot_pace: str | None = None, recruit_key: str | None = None) -> ParticipantRow:
    """A new participant at step 0 with their assignment (call inside the assignment's transaction); a pilot
    (simulated) participant when ``pilot_pace`` is given."""
    now = utcnow()
    row = ParticipantRow(study_id=study_id, public_id=public_id, token_hash=hash_token(token),
                         recruit_id=recruit_id, recruit_key=recruit_key, recruiting=recruiting,
                         config_hash=config_hash, plan=plan,
                         step=0, state=state, status="in_progress", test_run=test_run, excluded=False,
                         pilot=pilot_pace is not None, pilot_pace=pilot_pace,
                         created_at=now, updated_at=now)
    session.add(row)
    session.flush()
    session.add(AssignmentRow(study_id=study_id, participant_id=row.id, order_index=order_index,
                              condition_order=condition_order, created_at=now))
    session.flush()
    return row


def rotate_token(session: Session, participant_id: int, token: str) -> None:
    session.execute(update(ParticipantRow).where(ParticipantRow.id == participant_id)
                    .values(token_hash=hash_token(token), updated_at=utcnow()))


def advance(session: Session, participant_id: int, *, from_step: int, to_step: int, state: str,
            status: str, screen_out_reason: str | None = None) -> bool:
    """Move a participant from ``from_step`` to ``to_step`` (with the reason of a screen-out after a round);
    ``False`` if someone else moved them first."""
    now = utcnow()
    finished: datetime | None = now if status != "in_progress" else None
    result = session.execute(
        update(ParticipantRow)
        .where(ParticipantRow.id == participant_id, ParticipantRow.step == from_step,
               ParticipantRow.status == "in_progress")
        .values(step=to_step, state=state, status=status, updated_at=now, finished_at=finished,
                screen_out_reason=screen_out_reason)
    )
    return bool(result.rowcount)  # type: ignore[attr-defined]


def set_flags(session: Session, participant_id: int, *, test_run: bool | None, excluded: bool | None,
              reason: str | None) -> None:
    values: dict[str, Any] = {"updated_at": utcnow()}
    if test_run is not None:
        values["test_run"] = test_run
    if excluded is not None:
        values["excluded"] = excluded
        values["exclusion_reason"] = reason if excluded else None
    elif reason is not None:
        values["exclusion_reason"] = reason
    session.execute(update(ParticipantRow).where(ParticipantRow.id == participant_id).values(**values))


def list_participants(session: Session, study_id: str | None = None) -> list[tuple[ParticipantRow, AssignmentRow]]:
    query = (select(ParticipantRow, AssignmentRow)
             .join(AssignmentRow, AssignmentRow.participant_id == ParticipantRow.id)
             .order_by(ParticipantRow.id))
    if study_id is not None:
        query = query.where(ParticipantRow.study_id == study_id)
    return [(p, a) for p, a in session.execute(query)]
