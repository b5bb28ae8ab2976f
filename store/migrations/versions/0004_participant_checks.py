"""The participant's checks: the device their browser reported, comprehension-quiz attempts, free-text answers.

Revision ID: 0004
Revises: 0003
Create Date: 2026-12-01
"""

from __future__ import annotations

import sqlalchemy as sa
from alembic import op
from sqlalchemy.dialects import postgresql

revision = "0004"
down_revision = "0003"
branch_labels = None
depends_on = None

JSON = sa.JSON().with_variant(postgresql.JSONB(), "postgresql")


def upgrade() -> None:
    # Nullable columns without defaults: in-place ALTERs on SQLite and PostgreSQL (no table rewrite).
    op.add_column("participants", sa.Column("device", JSON, nullable=True))
    op.add_column("questionnaire_answers", sa.Column("text", sa.Text(), nullable=True))
    op.create_table(
        "quiz_attempts",
        sa.Column("id", sa.Integer(), autoincrement=True, nullable=False),
        sa.Column("participant_id", sa.Integer(), nullable=False),
        sa.Column("attempt", sa.Integer(), nullable=False),
        sa.Column("answers", JSON, nullable=False),
        sa.Column("wrong", JSON, nullable=False),
        sa.Column("passed", sa.Boolean(), nullable=False),
        sa.Column("created_at", sa.DateTime(timezone=True), nullable=False),
        sa.ForeignKeyConstraint(["participant_id"], ["participants.id"],
                                name="fk_quiz_attempts_participant_id_participants"),
        sa.PrimaryKeyConstraint("id", name="pk_quiz_attempts"),
        sa.UniqueConstraint("participant_id", "attempt", name="uq_quiz_attempts_participant_attempt"),
    )
    op.create_index("ix_quiz_attempts_participant_id", "quiz_attempts", ["participant_id"])


def downgrade() -> None:
    op.drop_index("ix_quiz_attempts_participant_id", table_name="quiz_attempts")
    op.drop_table("quiz_attempts")
    with op.batch_alter_table("questionnaire_answers") as batch:
        batch.drop_column("text")
    with op.batch_alter_table("participants") as batch:
        batch.drop_column("device")
