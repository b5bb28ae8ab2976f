"""Reading a study from the store: SQLAlchemy Core queries of the store's tables, never the running server.

The table definitions come from ``store.tables`` (the schema only: no app, route, game or flow
code is imported; data flows one way: server writes, analysis reads). Everything is returned as frozen records, so
the measures and the export are pure functions of what is stored. Large columns the analysis does not need (the full KB
state, the robot's decision record) are never loaded.

A study can be exported while a server keeps writing to it, so the reads of one export must see one
snapshot: :func:`open_engine` gives the store's snapshot engine (:func:`store.engine.snapshot_engine`: SQLite an
explicit deferred ``BEGIN``, which in WAL mode reads one version of the file and takes no write lock; PostgreSQL
``REPEATABLE READ``), and the caller reads everything on one connection.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from datetime import datetime
from typing import Any

from sqlalchemy import Connection, Engine, func, inspect, select
from sqlalchemy.exc import SQLAlchemyError

from analysis.source.input_errors import AnalysisInputError
from planner.kb import KnowledgeBase
from planner.state import WorldState
from planner.summary import info_diff, state_info
from store.engine import NoStoreError, snapshot_engine
from store.migrate import current_revision, head_revision
from store.tables import AnswerRow, AssignmentRow, EventRow, ParticipantRow, StudyRow, TickRow, TrialRow


class StoreReadError(AnalysisInputError):
    """The store cannot be read for this study: no database, no schema, or no such study."""


class UnknownStudyError(StoreReadError):
    """The store has no study with this id."""


@dataclass(frozen=True, slots=True)
class StoredParticipant:
    id: int
    public_id: str
    recruit_id: str | None
    recruiting: dict[str, str]
    status: str
    state: str
    step: int
    steps: int
    test_run: bool
    excluded: bool
    exclusion_reason: str | None
    created_at: datetime
    finished_at: datetime | None
    order_index: int | None
    condition_order: tuple[str, ...]
    pilot: bool = False
    """A simulated pilot participant (``steakhouse pilot``); read only when pilots are asked for."""


@dataclass(frozen=True, slots=True)
class StoredTrial:
    id: int
    participant_id: int
    kind: str
    index: int
    attempt: int
    condition: str
    kitchen: str
    robot: str
    view: str
    fov_angle: float | None
    """Degrees; ``None`` for a trial stored before angles were recorded (``store.tables.TrialRow``)."""
    seed: int
    config_hash: str
    status: str
    end_reason: str | None
    started_at: datetime
    ended_at: datetime | None
    ticks: int
    delivered: int
    score: int
    initial_state: dict[str, Any]
    decisions: int | None = None
    """Robot decisions the trial made; ``None`` for trials stored before the server counted them."""
    missed_decisions: int | None = None
    invalid_reason: str | None = None
    """Why the server marked the trial invalid (robot decisions past their deadline); ``None`` when valid."""
    key_actions: int | None = None
    idle_pct: float | None = None
    refused_steps: int | None = None
    delivered_by_participant: int | None = None
    delivered_by_robot: int | None = None
    task_steps: int | None = None
    robot_task_steps: int | None = None
    stand_ticks: int | None = None
    think_seconds: float | None = None
    """The participant's activity the server stored when the trial ended (``None``: not recorded)."""
    engagement_reason: str | None = None
    """Why the server marked the main trial ``low_engagement``; ``None`` when the participant took part."""

    @property
    def invalid(self) -> bool:
        """Not analysable data: the robot's health or the participant's engagement failed."""
        return bool(self.invalid_reason or self.engagement_reason)

    @property
    def invalid_why(self) -> str | None:
        return self.invalid_reason or self.engagement_reason or None


@dataclass(frozen=True, slots=True)
class StoredTick:
    """One stored world step (the columns of ``ticks`` the analysis uses)."""

    tick: int
    human_action: str
    robot_action: str
    action_source: str
    subtask: str | None
    kb_summary: dict[str, Any]
    world_summary: dict[str, Any]
    kb_gap: dict[str, int]
    kb_gap_total: int
    robot_in_fov: bool
    lateness_ms: float
    decision_ms: float | None
    robot_missed: bool
    world_state: dict[str, Any]
    controller: dict[str, Any]
    recorded_at: datetime | None = None
    world_events: list[dict[str, Any]] | None = None
    """The step's world events (agent, kind, pos, obj); ``None`` for ticks stored before they were kept."""
    round_seconds: float | None = None
    """Seconds the round had run while the participant was connected; ``None`` for ticks stored before."""
    kb_diff: dict[str, int] | None = None
    """The reference's KB gap per component (``ticks.kb_diff``; for ticks stored before it was kept, computed by
    :func:`read_ticks` from the stored world and KB)."""


@dataclass(frozen=True, slots=True)
class StoredEvent:
    trial_id: int | None
    tick: int | None
    kind: str
    payload: dict[str, Any]
    created_at: datetime | None = None


@dataclass(frozen=True, slots=True)
class StoredAnswer:
    participant_id: int
    questionnaire_id: str
    step: int
    after_trial: int | None
    trial_id: int | None
    item_id: str
    value: int | None
    created_at: datetime
    text: str | None = None
    """A free-text answer, or the chosen option's text of a choice item."""


@dataclass(frozen=True, slots=True)
class StudyData:
    """A study's rows: participants (with their assignment), trial attempts, questionnaire answers."""

    id: str
    title: str
    config_hash: str
    config: dict[str, Any]
    participants: tuple[StoredParticipant, ...]
    trials: tuple[StoredTrial, ...]
    answers: tuple[StoredAnswer, ...]
    pilots_left_out: int = 0
    """Simulated pilot participants of the study in the store that were not read (``include_pilot`` false)."""


def open_engine(url: str) -> Engine:
    """An engine for reading the store at ``url`` (the store's snapshot engine); a SQLite file that does not exist
    is an error (reading must never create an empty database)."""
    try:
        return snapshot_engine(url)
    except NoStoreError as exc:
        raise StoreReadError(str(exc)) from exc


def study_ids(conn: Connection) -> list[str]:
    """The ids of the studies in the store."""
    return list(conn.scalars(select(StudyRow.id).order_by(StudyRow.id)))


def read_study(conn: Connection, study_id: str, include_pilot: bool = False) -> StudyData:
    """Everything stored about ``study_id`` except ticks and events (read per trial, see below). Simulated pilot
    participants, their trials and answers are left out unless ``include_pilot``."""
    try:
        missing = {"studies", "participants", "trials", "ticks", "events"} - set(inspect(conn).get_table_names())
    except SQLAlchemyError as exc:
        raise StoreReadError(f"cannot read the store: {exc}") from exc
    if missing:
        raise StoreReadError(f"the database has no Steakhouse store (tables missing: {', '.join(sorted(missing))})")
    _check_schema(conn)
    study = conn.execute(select(StudyRow.title, StudyRow.config_hash, StudyRow.config)
                         .where(StudyRow.id == study_id)).first()
    if study is None:
        known = ", ".join(study_ids(conn)) or "none"
        raise UnknownStudyError(f"no study {study_id!r} in the store; studies stored: {known}")
    return StudyData(id=study_id, title=study.title, config_hash=study.config_hash, config=dict(study.config),
                     participants=_participants(conn, study_id, include_pilot),
                     trials=_trials(conn, study_id, include_pilot), answers=_answers(conn, study_id, include_pilot),
                     pilots_left_out=0 if include_pilot else _pilot_count(conn, study_id))


def _pilot_count(conn: Connection, study_id: str) -> int:
    p = ParticipantRow
    return int(conn.scalar(select(func.count(p.id)).where(p.study_id == study_id, p.pilot.is_(True))) or 0)


def _check_schema(conn: Connection) -> None:
    """Reading never migrates: a store written by an older (or newer) version of the platform is refused with
    what to do, rather than failing on a missing column."""
    stored, head = current_revision(conn), head_revision()
    if stored != head:
        raise StoreReadError(
            f"the store's schema is at revision {stored}, this version of the platform reads revision {head}: "
            f"start `steakhouse serve` once on this database (it migrates the store at start), then read it again")


def read_ticks(conn: Connection, trial_id: int) -> list[StoredTick]:
    """The stored ticks of one trial, in tick order."""
    rows = conn.execute(select(
        TickRow.tick, TickRow.human_action, TickRow.robot_action, TickRow.action_source, TickRow.subtask,
        TickRow.kb_summary, TickRow.world_summary, TickRow.kb_gap, TickRow.kb_gap_total, TickRow.robot_in_fov,
        TickRow.lateness_ms, TickRow.decision_ms, TickRow.robot_missed, TickRow.world_state, TickRow.controller,
        TickRow.recorded_at, TickRow.world_events, TickRow.round_seconds, TickRow.kb_diff,
    ).where(TickRow.trial_id == trial_id).order_by(TickRow.tick))
    ticks = [StoredTick(**row._asdict()) for row in rows]
    if any(t.kb_diff is None for t in ticks):
        ticks = _with_kb_diff(conn, trial_id, ticks)
    return ticks


def _with_kb_diff(conn: Connection, trial_id: int, ticks: list[StoredTick]) -> list[StoredTick]:
    """Ticks stored before ``kb_diff`` was kept get it from their stored world and KB states (the reference's
    state info of each, ``planner.summary``)."""
    query = select(TickRow.tick, TickRow.kb_state).where(TickRow.trial_id == trial_id)
    kb_states: dict[int, dict[str, Any]] = {row.tick: row.kb_state for row in conn.execute(query)}
    out = []
    for t in ticks:
        if t.kb_diff is None:
            kb = KnowledgeBase.from_dict(kb_states[t.tick])
            t = replace(t, kb_diff=info_diff(state_info(kb), state_info(WorldState.from_dict(t.world_state))))
        out.append(t)
    return out


def _real(query: Any, include_pilot: bool) -> Any:
    """``query`` (joined with participants) without pilot participants unless ``include_pilot``."""
    return query if include_pilot else query.where(ParticipantRow.pilot.is_(False))


def read_events(conn: Connection, study_id: str) -> dict[int, list[StoredEvent]]:
    """The events of every trial of the study, by trial id, in the order they were logged."""
    rows = conn.execute(
        select(EventRow.trial_id, EventRow.tick, EventRow.kind, EventRow.payload, EventRow.created_at)
        .join(TrialRow, TrialRow.id == EventRow.trial_id)
        .where(TrialRow.study_id == study_id)
        .order_by(EventRow.id))
    out: dict[int, list[StoredEvent]] = {}
    for row in rows:
        out.setdefault(row.trial_id, []).append(StoredEvent(**row._asdict()))
    return out


def _participants(conn: Connection, study_id: str, include_pilot: bool) -> tuple[StoredParticipant, ...]:
    p = ParticipantRow
    rows = conn.execute(_real(
        select(p.id, p.public_id, p.recruit_id, p.recruiting, p.status, p.state, p.step, p.plan, p.test_run,
               p.excluded, p.exclusion_reason, p.created_at, p.finished_at, AssignmentRow.order_index,
               AssignmentRow.condition_order, p.pilot)
        .outerjoin(AssignmentRow, AssignmentRow.participant_id == p.id)
        .where(p.study_id == study_id), include_pilot)
        .order_by(p.id))
    return tuple(StoredParticipant(
        id=r.id, public_id=r.public_id, recruit_id=r.recruit_id, recruiting=dict(r.recruiting or {}),
        status=r.status, state=r.state, step=r.step, steps=len(r.plan or ()), test_run=bool(r.test_run),
        excluded=bool(r.excluded), exclusion_reason=r.exclusion_reason, created_at=r.created_at,
        finished_at=r.finished_at, order_index=r.order_index, condition_order=tuple(r.condition_order or ()),
        pilot=bool(r.pilot))
        for r in rows)


def _trials(conn: Connection, study_id: str, include_pilot: bool) -> tuple[StoredTrial, ...]:
    t = TrialRow
    rows = conn.execute(_real(
        select(t.id, t.participant_id, t.kind, t.index, t.attempt, t.condition_id.label("condition"), t.kitchen,
               t.robot, t.view, t.fov_angle, t.seed, t.config_hash, t.status, t.end_reason, t.started_at, t.ended_at,
               t.ticks,
               t.delivered, t.score, t.initial_state, t.decisions, t.missed_decisions, t.invalid_reason,
               t.key_actions, t.idle_pct, t.refused_steps, t.delivered_by_participant, t.delivered_by_robot,
               t.task_steps, t.robot_task_steps, t.stand_ticks, t.think_seconds, t.engagement_reason)
        .join(ParticipantRow, ParticipantRow.id == t.participant_id)
        .where(t.study_id == study_id), include_pilot)
        .order_by(t.id))
    return tuple(StoredTrial(**row._asdict()) for row in rows)


def _answers(conn: Connection, study_id: str, include_pilot: bool) -> tuple[StoredAnswer, ...]:
    rows = conn.execute(_real(
        select(AnswerRow.participant_id, AnswerRow.questionnaire_id, AnswerRow.step, AnswerRow.after_trial,
               AnswerRow.trial_id, AnswerRow.item_id, AnswerRow.value, AnswerRow.created_at, AnswerRow.text)
        .join(ParticipantRow, ParticipantRow.id == AnswerRow.participant_id)
        .where(ParticipantRow.study_id == study_id), include_pilot)
        .order_by(AnswerRow.participant_id, AnswerRow.step, AnswerRow.id))
    return tuple(StoredAnswer(**row._asdict()) for row in rows)


def iso_time(value: datetime | None) -> str | None:
    """A stored (UTC) timestamp as ISO 8601 text, ``None`` kept."""
    return None if value is None else value.isoformat()
