"""Initial schema: studies, participants, assignments, trials, ticks, events, questionnaire answers.

Revision ID: 0001
Revises:
Create Date: 2026-11-22
"""

from __future__ import annotations

import sqlalchemy as sa
from alembic import op
from sqlalchemy.dialects import postgresql

revision = "0001"
down_revision = None
branch_labels = None
depends_on = None

JSON = sa.JSON().with_variant(postgresql.JSONB(), "postgresql")


def _ts(name: str, nullable: bool = False) -> sa.Column[object]:
    return sa.Column(name, sa.DateTime(timezone=True), nullable=nullable)


def upgrade() -> None:
    op.create_table(
        "studies",
        sa.Column("id", sa.String(64), nullable=False),
        sa.Column("title", sa.Text(), nullable=False),
        sa.Column("config_hash", sa.String(64), nullable=False),
        sa.Column("config", JSON, nullable=False),
        sa.Column("orders", JSON, nullable=False),
        _ts("created_at"),
        _ts("updated_at"),
        sa.PrimaryKeyConstraint("id", name="pk_studies"),
    )
    op.create_table(
        "participants",
        sa.Column("id", sa.Integer(), autoincrement=True, nullable=False),
        sa.Column("public_id", sa.String(32), nullable=False),
        sa.Column("study_id", sa.String(64), nullable=False),
        sa.Column("token_hash", sa.String(64), nullable=False),
        sa.Column("recruit_id", sa.String(200), nullable=True),
        sa.Column("recruiting", JSON, nullable=False),
        sa.Column("config_hash", sa.String(64), nullable=False),
        sa.Column("plan", JSON, nullable=False),
        sa.Column("step", sa.Integer(), nullable=False),
        sa.Column("state", sa.String(32), nullable=False),
        sa.Column("status", sa.String(16), nullable=False),
        sa.Column("test_run", sa.Boolean(), nullable=False),
        sa.Column("excluded", sa.Boolean(), nullable=False),
        sa.Column("exclusion_reason", sa.Text(), nullable=True),
        _ts("created_at"),
        _ts("updated_at"),
        _ts("finished_at", nullable=True),
        sa.ForeignKeyConstraint(["study_id"], ["studies.id"], name="fk_participants_study_id_studies"),
        sa.PrimaryKeyConstraint("id", name="pk_participants"),
        sa.UniqueConstraint("public_id", name="uq_participants_public_id"),
        sa.UniqueConstraint("study_id", "recruit_id", name="uq_participants_study_recruit"),
        sa.UniqueConstraint("token_hash", name="uq_participants_token_hash"),
    )
    op.create_index("ix_participants_study_id", "participants", ["study_id"])
    op.create_table(
        "assignments",
        sa.Column("id", sa.Integer(), autoincrement=True, nullable=False),
        sa.Column("study_id", sa.String(64), nullable=False),
        sa.Column("participant_id", sa.Integer(), nullable=False),
        sa.Column("order_index", sa.Integer(), nullable=False),
        sa.Column("condition_order", JSON, nullable=False),
        _ts("created_at"),
        sa.ForeignKeyConstraint(["participant_id"], ["participants.id"],
                                name="fk_assignments_participant_id_participants"),
        sa.ForeignKeyConstraint(["study_id"], ["studies.id"], name="fk_assignments_study_id_studies"),
        sa.PrimaryKeyConstraint("id", name="pk_assignments"),
        sa.UniqueConstraint("participant_id", name="uq_assignments_participant_id"),
    )
    op.create_index("ix_assignments_study_id", "assignments", ["study_id"])
    op.create_table(
        "trials",
        sa.Column("id", sa.Integer(), autoincrement=True, nullable=False),
        sa.Column("study_id", sa.String(64), nullable=False),
        sa.Column("participant_id", sa.Integer(), nullable=False),
        sa.Column("kind", sa.String(16), nullable=False),
        sa.Column("index", sa.Integer(), nullable=False),
        sa.Column("attempt", sa.Integer(), nullable=False),
        sa.Column("condition_id", sa.String(140), nullable=False),
        sa.Column("kitchen", sa.String(64), nullable=False),
        sa.Column("robot", sa.String(64), nullable=False),
        sa.Column("seed", sa.BigInteger(), nullable=False),
        sa.Column("config_hash", sa.String(64), nullable=False),
        sa.Column("status", sa.String(16), nullable=False),
        sa.Column("end_reason", sa.String(32), nullable=True),
        _ts("started_at"),
        _ts("ended_at", nullable=True),
        _ts("last_active_at"),
        sa.Column("ticks", sa.Integer(), nullable=False),
        sa.Column("delivered", sa.Integer(), nullable=False),
        sa.Column("score", sa.Integer(), nullable=False),
        sa.Column("initial_state", JSON, nullable=False),
        sa.ForeignKeyConstraint(["participant_id"], ["participants.id"], name="fk_trials_participant_id_participants"),
        sa.ForeignKeyConstraint(["study_id"], ["studies.id"], name="fk_trials_study_id_studies"),
        sa.PrimaryKeyConstraint("id", name="pk_trials"),
        sa.UniqueConstraint("participant_id", "kind", "index", "attempt", name="uq_trials_attempt"),
    )
    op.create_index("ix_trials_participant_id", "trials", ["participant_id"])
    op.create_index("ix_trials_status", "trials", ["status"])
    op.create_index("ix_trials_study_id", "trials", ["study_id"])
    op.create_table(
        "events",
        sa.Column("id", sa.Integer(), autoincrement=True, nullable=False),
        sa.Column("participant_id", sa.Integer(), nullable=False),
        sa.Column("trial_id", sa.Integer(), nullable=True),
        sa.Column("tick", sa.Integer(), nullable=True),
        sa.Column("kind", sa.String(32), nullable=False),
        sa.Column("payload", JSON, nullable=False),
        _ts("created_at"),
        sa.ForeignKeyConstraint(["participant_id"], ["participants.id"], name="fk_events_participant_id_participants"),
        sa.ForeignKeyConstraint(["trial_id"], ["trials.id"], name="fk_events_trial_id_trials"),
        sa.PrimaryKeyConstraint("id", name="pk_events"),
    )
    op.create_index("ix_events_participant_id", "events", ["participant_id"])
    op.create_index("ix_events_trial_id", "events", ["trial_id"])
    op.create_table(
        "questionnaire_answers",
        sa.Column("id", sa.Integer(), autoincrement=True, nullable=False),
        sa.Column("participant_id", sa.Integer(), nullable=False),
        sa.Column("questionnaire_id", sa.String(64), nullable=False),
        sa.Column("step", sa.Integer(), nullable=False),
        sa.Column("after_trial", sa.Integer(), nullable=True),
        sa.Column("trial_id", sa.Integer(), nullable=True),
        sa.Column("item_id", sa.String(64), nullable=False),
        sa.Column("value", sa.Integer(), nullable=True),
        _ts("created_at"),
        sa.ForeignKeyConstraint(["participant_id"], ["participants.id"],
                                name="fk_questionnaire_answers_participant_id_participants"),
        sa.ForeignKeyConstraint(["trial_id"], ["trials.id"], name="fk_questionnaire_answers_trial_id_trials"),
        sa.PrimaryKeyConstraint("id", name="pk_questionnaire_answers"),
        sa.UniqueConstraint("participant_id", "step", "item_id", name="uq_answers_step_item"),
    )
    op.create_index("ix_questionnaire_answers_participant_id", "questionnaire_answers", ["participant_id"])
    op.create_table(
        "ticks",
        sa.Column("trial_id", sa.Integer(), nullable=False),
        sa.Column("tick", sa.Integer(), nullable=False),
        _ts("recorded_at"),
        sa.Column("human_action", sa.String(16), nullable=False),
        sa.Column("robot_action", sa.String(16), nullable=False),
        sa.Column("action_source", sa.String(16), nullable=False),
        sa.Column("subtask", sa.String(32), nullable=True),
        sa.Column("kb_summary", JSON, nullable=False),
        sa.Column("world_summary", JSON, nullable=False),
        sa.Column("kb_gap", JSON, nullable=False),
        sa.Column("kb_gap_total", sa.Integer(), nullable=False),
        sa.Column("robot_in_fov", sa.Boolean(), nullable=False),
        sa.Column("lateness_ms", sa.Float(), nullable=False),
        sa.Column("decision_ms", sa.Float(), nullable=True),
        sa.Column("robot_missed", sa.Boolean(), nullable=False),
        sa.Column("robot_info", JSON, nullable=True),
        sa.Column("world_state", JSON, nullable=False),
        sa.Column("kb_state", JSON, nullable=False),
        sa.Column("controller", JSON, nullable=False),
        sa.ForeignKeyConstraint(["trial_id"], ["trials.id"], name="fk_ticks_trial_id_trials"),
        sa.PrimaryKeyConstraint("trial_id", "tick", name="pk_ticks"),
    )


def downgrade() -> None:
    for table in ("ticks", "questionnaire_answers", "events", "trials", "assignments", "participants", "studies"):
        op.drop_table(table)
