"""The store's tables (SQLAlchemy 2 declarative, typed). The Alembic migrations create exactly these.

- ``studies``: one row per study id served (title, resolved config and its hash, condition orders).
- ``participants``: recruiting ids, the hash of their token (never the token), their step plan and
  progress, test-run / exclusion flags with a reason.
- ``assignments``: the condition order each participant got (index into the study's orders).
- ``trials``: one row per attempt at a practice or main trial: condition, kitchen, robot, view, FOV angle, seed, config
  hash, status (``running`` / ``finished`` / ``abandoned``) and outcome (ticks, delivered, score).
- ``ticks``: one row per world step (primary key ``(trial_id, tick)``, so a tick can never be stored
  twice): joint action, the participant's subtask, modelled KB and world summaries (with the reference's state
  info), KB-gap components (ours, and the reference's per-component gap ``kb_diff``),
  robot in the participant's FOV, tick lateness, robot decision time, and the full world and KB state
  (replay and resume read them).
- ``events``: selections, interrupts, connection, focus and idle events, errors, missed deadlines.
- ``questionnaire_answers``: one row per answered item: ``value`` (a rating, or a choice's 0-based index) and
  ``text`` (a free-text answer, or the chosen option's text).
- ``quiz_attempts``: one row per submission of the comprehension quiz: the answers, the questions got wrong.
"""

from __future__ import annotations

from datetime import datetime
from typing import Any

from sqlalchemy import (
    BigInteger,
    Boolean,
    Float,
    ForeignKey,
    Index,
    Integer,
    MetaData,
    String,
    Text,
    UniqueConstraint,
    false,
)
from sqlalchemy.orm import DeclarativeBase, Mapped, mapped_column

from store.types import JsonType, UTCDateTime, utcnow

NAMING = {
    "ix": "ix_%(column_0_label)s",
    "uq": "uq_%(table_name)s_%(column_0_name)s",
    "ck": "ck_%(table_name)s_%(constraint_name)s",
    "fk": "fk_%(table_name)s_%(column_0_name)s_%(referred_table_name)s",
    "pk": "pk_%(table_name)s",
}


class Base(DeclarativeBase):
    metadata = MetaData(naming_convention=NAMING)


class StudyRow(Base):
    __tablename__ = "studies"

    id: Mapped[str] = mapped_column(String(64), primary_key=True)
    title: Mapped[str] = mapped_column(Text)
    config_hash: Mapped[str] = mapped_column(String(64))
    config: Mapped[dict[str, Any]] = mapped_column(JsonType)
    orders: Mapped[list[list[str]]] = mapped_column(JsonType)
    created_at: Mapped[datetime] = mapped_column(UTCDateTime, default=utcnow)
    updated_at: Mapped[datetime] = mapped_column(UTCDateTime, default=utcnow)


class ParticipantRow(Base):
    __tablename__ = "participants"
    __table_args__ = (UniqueConstraint("study_id", "recruit_id", name="uq_participants_study_recruit"),)

    id: Mapped[int] = mapped_column(Integer, primary_key=True, autoincrement=True)
    public_id: Mapped[str] = mapped_column(String(32), unique=True)
    study_id: Mapped[str] = mapped_column(ForeignKey("studies.id"), index=True)
    token_hash: Mapped[str] = mapped_column(String(64), unique=True)
    recruit_id: Mapped[str | None] = mapped_column(String(200))
    recruiting: Mapped[dict[str, str]] = mapped_column(JsonType, default=dict)
    config_hash: Mapped[str] = mapped_column(String(64))
    plan: Mapped[list[dict[str, Any]]] = mapped_column(JsonType)
    step: Mapped[int] = mapped_column(Integer, default=0)
    state: Mapped[str] = mapped_column(String(32))
    status: Mapped[str] = mapped_column(String(16), default="in_progress")
    test_run: Mapped[bool] = mapped_column(Boolean, default=False)
    pilot: Mapped[bool] = mapped_column(Boolean, default=False, server_default=false())
    """A simulated participant of ``steakhouse pilot``: never counted for assignment or as a real participant,
    left out of exports and analyses unless asked (``--include-pilot``)."""
    pilot_pace: Mapped[str | None] = mapped_column(String(16), nullable=True)
    """A pilot's trial pace (``fast``: a step as soon as the robot decided and the simulated participant
    answered; ``realtime``: the study's rate); NULL for real participants, whose pace is always the study's."""
    excluded: Mapped[bool] = mapped_column(Boolean, default=False)
    exclusion_reason: Mapped[str | None] = mapped_column(Text)
    created_at: Mapped[datetime] = mapped_column(UTCDateTime, default=utcnow)
    updated_at: Mapped[datetime] = mapped_column(UTCDateTime, default=utcnow)
    finished_at: Mapped[datetime | None] = mapped_column(UTCDateTime)
    device: Mapped[dict[str, Any] | None] = mapped_column(JsonType, nullable=True)
    """The device the participant's browser last reported (``study_config.study.device.DeviceInfo`` fields, plus
    ``problems`` and ``checked_at``); NULL until it reports one."""
    uncounted_reason: Mapped[str | None] = mapped_column(String(200), nullable=True)
    """Why the participant no longer counts toward their condition order (``server.flow.standing``: a main
    round that cannot become an analysable cell, or a refused device); NULL while they count."""
    screen_out_reason: Mapped[str | None] = mapped_column(String(32), nullable=True)
    """Why a participant screened out after a round was screened out (``abandoned_rounds``,
    ``low_engagement``); NULL otherwise (the other reasons follow from the step they stopped at)."""


class AssignmentRow(Base):
    __tablename__ = "assignments"

    id: Mapped[int] = mapped_column(Integer, primary_key=True, autoincrement=True)
    study_id: Mapped[str] = mapped_column(ForeignKey("studies.id"), index=True)
    participant_id: Mapped[int] = mapped_column(ForeignKey("participants.id"), unique=True)
    order_index: Mapped[int] = mapped_column(Integer)
    condition_order: Mapped[list[str]] = mapped_column(JsonType)
    created_at: Mapped[datetime] = mapped_column(UTCDateTime, default=utcnow)


class TrialRow(Base):
    __tablename__ = "trials"
    __table_args__ = (
        UniqueConstraint("participant_id", "kind", "index", "attempt", name="uq_trials_attempt"),
        Index("ix_trials_status", "status"),
    )

    id: Mapped[int] = mapped_column(Integer, primary_key=True, autoincrement=True)
    study_id: Mapped[str] = mapped_column(ForeignKey("studies.id"), index=True)
    participant_id: Mapped[int] = mapped_column(ForeignKey("participants.id"), index=True)
    kind: Mapped[str] = mapped_column(String(16))
    index: Mapped[int] = mapped_column(Integer)
    attempt: Mapped[int] = mapped_column(Integer, default=1)
    condition_id: Mapped[str] = mapped_column(String(140))
    kitchen: Mapped[str] = mapped_column(String(64))
    robot: Mapped[str] = mapped_column(String(64))
    view: Mapped[str] = mapped_column(String(16), server_default="top_down")
    """How the participant saw the kitchen (``study_config.study.views``); ``top_down`` for trials stored before
    revision 0003."""
    fov_angle: Mapped[float | None] = mapped_column(Float, nullable=True)
    """The participant's field of view in degrees (``study_config.study.fov_angles``); for trials stored before
    revision 0008, the angle of the study's stored configuration when it is the one they were played with, else
    ``NULL`` (unknown)."""
    seed: Mapped[int] = mapped_column(BigInteger)
    config_hash: Mapped[str] = mapped_column(String(64))
    status: Mapped[str] = mapped_column(String(16), default="running")
    end_reason: Mapped[str | None] = mapped_column(String(32))
    started_at: Mapped[datetime] = mapped_column(UTCDateTime, default=utcnow)
    ended_at: Mapped[datetime | None] = mapped_column(UTCDateTime)
    last_active_at: Mapped[datetime] = mapped_column(UTCDateTime, default=utcnow)
    ticks: Mapped[int] = mapped_column(Integer, default=0)
    delivered: Mapped[int] = mapped_column(Integer, default=0)
    score: Mapped[int] = mapped_column(Integer, default=0)
    initial_state: Mapped[dict[str, Any]] = mapped_column(JsonType)
    decisions: Mapped[int | None] = mapped_column(Integer, nullable=True)
    """Robot decisions the loop asked for (one per world step); NULL for trials stored before revision 0005."""
    missed_decisions: Mapped[int | None] = mapped_column(Integer, nullable=True)
    """Of these, the ones that missed their deadline (the robot stood still)."""
    invalid_reason: Mapped[str | None] = mapped_column(String(200), nullable=True)
    """Why the trial is not valid data (``server.game.health``); NULL when it is valid."""
    selections: Mapped[int | None] = mapped_column(Integer, nullable=True)
    """The participant's task choices (``store.activity``; NULL until the trial ended, and for trials
    stored before revision 0007)."""
    interrupts: Mapped[int | None] = mapped_column(Integer, nullable=True)
    """The participant's accepted interrupts (keys and the stop button)."""
    key_actions: Mapped[int | None] = mapped_column(Integer, nullable=True)
    """Of these, the one-step key actions (moves, stay, interact)."""
    idle_pct: Mapped[float | None] = mapped_column(Float, nullable=True)
    """The share of the trial's tick periods in which the cook had nothing to do (in %)."""
    refused_steps: Mapped[int | None] = mapped_column(Integer, nullable=True)
    """The participant's tasks refused or ended because they could not work (``subtask_blocked`` events)."""
    delivered_by_participant: Mapped[int | None] = mapped_column(Integer, nullable=True)
    """Dishes the participant's cook delivered."""
    delivered_by_robot: Mapped[int | None] = mapped_column(Integer, nullable=True)
    """Dishes the robot delivered."""
    engagement_reason: Mapped[str | None] = mapped_column(String(200), nullable=True)
    """Why the main trial is ``low_engagement`` (``server.flow.engagement``); NULL when the participant took
    part."""


class TickRow(Base):
    __tablename__ = "ticks"

    trial_id: Mapped[int] = mapped_column(ForeignKey("trials.id"), primary_key=True)
    tick: Mapped[int] = mapped_column(Integer, primary_key=True)
    recorded_at: Mapped[datetime] = mapped_column(UTCDateTime)
    human_action: Mapped[str] = mapped_column(String(16))
    robot_action: Mapped[str] = mapped_column(String(16))
    action_source: Mapped[str] = mapped_column(String(16))
    subtask: Mapped[str | None] = mapped_column(String(32))
    kb_summary: Mapped[dict[str, Any]] = mapped_column(JsonType)
    world_summary: Mapped[dict[str, Any]] = mapped_column(JsonType)
    kb_gap: Mapped[dict[str, int]] = mapped_column(JsonType)
    kb_gap_total: Mapped[int] = mapped_column(Integer)
    robot_in_fov: Mapped[bool] = mapped_column(Boolean)
    lateness_ms: Mapped[float] = mapped_column(Float)
    decision_ms: Mapped[float | None] = mapped_column(Float)
    robot_missed: Mapped[bool] = mapped_column(Boolean, default=False)
    robot_info: Mapped[dict[str, Any] | None] = mapped_column(JsonType)
    world_state: Mapped[dict[str, Any]] = mapped_column(JsonType)
    kb_state: Mapped[dict[str, Any]] = mapped_column(JsonType)
    controller: Mapped[dict[str, Any]] = mapped_column(JsonType)
    world_events: Mapped[list[dict[str, Any]] | None] = mapped_column(JsonType, nullable=True)
    """The step's world events (``planner.events.Event.to_dict``: agent, kind, pos, obj); NULL in ticks
    stored before revision 0002."""
    round_seconds: Mapped[float | None] = mapped_column(Float, nullable=True)
    """Wall-clock seconds the round had run at this tick while the participant was connected (what
    ``timing.max_round_seconds`` limits; a round resumed from the store goes on from it); NULL in ticks stored
    before revision 0009."""
    kb_diff: Mapped[dict[str, int] | None] = mapped_column(JsonType, nullable=True)
    """The reference's KB gap at this tick, per component (grill, board, sink, robot_held;
    ``planner.summary.info_diff``), from the ``reference`` state info of ``kb_summary`` and ``world_summary``
    (the writer fills it when the row does not bring it); NULL in ticks stored before revision 0010."""


class EventRow(Base):
    __tablename__ = "events"

    id: Mapped[int] = mapped_column(Integer, primary_key=True, autoincrement=True)
    participant_id: Mapped[int] = mapped_column(ForeignKey("participants.id"), index=True)
    trial_id: Mapped[int | None] = mapped_column(ForeignKey("trials.id"), index=True)
    tick: Mapped[int | None] = mapped_column(Integer)
    kind: Mapped[str] = mapped_column(String(32))
    payload: Mapped[dict[str, Any]] = mapped_column(JsonType, default=dict)
    created_at: Mapped[datetime] = mapped_column(UTCDateTime, default=utcnow)


class AnswerRow(Base):
    __tablename__ = "questionnaire_answers"
    __table_args__ = (UniqueConstraint("participant_id", "step", "item_id", name="uq_answers_step_item"),)

    id: Mapped[int] = mapped_column(Integer, primary_key=True, autoincrement=True)
    participant_id: Mapped[int] = mapped_column(ForeignKey("participants.id"), index=True)
    questionnaire_id: Mapped[str] = mapped_column(String(64))
    step: Mapped[int] = mapped_column(Integer)
    after_trial: Mapped[int | None] = mapped_column(Integer)
    trial_id: Mapped[int | None] = mapped_column(ForeignKey("trials.id"))
    item_id: Mapped[str] = mapped_column(String(64))
    value: Mapped[int | None] = mapped_column(Integer)
    text: Mapped[str | None] = mapped_column(Text, nullable=True)
    """A free-text answer, or the chosen option's text for a choice item; NULL for ratings."""
    created_at: Mapped[datetime] = mapped_column(UTCDateTime, default=utcnow)


class QuizAttemptRow(Base):
    __tablename__ = "quiz_attempts"
    __table_args__ = (UniqueConstraint("participant_id", "attempt", name="uq_quiz_attempts_participant_attempt"),)

    id: Mapped[int] = mapped_column(Integer, primary_key=True, autoincrement=True)
    participant_id: Mapped[int] = mapped_column(ForeignKey("participants.id"), index=True)
    attempt: Mapped[int] = mapped_column(Integer)
    """1, 2, … per participant."""
    answers: Mapped[dict[str, int]] = mapped_column(JsonType)
    """Question id → the chosen option's 0-based index."""
    wrong: Mapped[list[str]] = mapped_column(JsonType)
    """Ids of the questions answered wrongly (empty when passed)."""
    passed: Mapped[bool] = mapped_column(Boolean)
    created_at: Mapped[datetime] = mapped_column(UTCDateTime, default=utcnow)
