"""Participation: per-trial activity of the participant, low engagement, why a participant stopped counting for
assignment and why they were screened out (docs/operations.md, "Engagement").

Revision ID: 0007
Revises: 0006
Create Date: 2026-12-03
"""

from __future__ import annotations

import sqlalchemy as sa
from alembic import op

revision = "0007"
down_revision = "0006"
branch_labels = None
depends_on = None

TRIAL_COUNTS = ("selections", "interrupts", "key_actions", "refused_steps", "delivered_by_participant",
                "delivered_by_robot")


def upgrade() -> None:
    # Nullable columns without defaults: NULL for trials stored before this revision (unknown, not zero).
    for name in TRIAL_COUNTS:
        op.add_column("trials", sa.Column(name, sa.Integer(), nullable=True))
    op.add_column("trials", sa.Column("idle_pct", sa.Float(), nullable=True))
    op.add_column("trials", sa.Column("engagement_reason", sa.String(length=200), nullable=True))
    op.add_column("participants", sa.Column("uncounted_reason", sa.String(length=200), nullable=True))
    op.add_column("participants", sa.Column("screen_out_reason", sa.String(length=32), nullable=True))


def downgrade() -> None:
    with op.batch_alter_table("participants") as batch:
        batch.drop_column("screen_out_reason")
        batch.drop_column("uncounted_reason")
    with op.batch_alter_table("trials") as batch:
        batch.drop_column("engagement_reason")
        batch.drop_column("idle_pct")
        for name in reversed(TRIAL_COUNTS):
            batch.drop_column(name)
