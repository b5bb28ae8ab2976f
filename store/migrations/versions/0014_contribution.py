"""Contribution: per trial, the participant's and the robot's task steps (interactions that changed the world), the
ticks in which the participant had no executable action, and the participant's wall-clock think time
(docs/operations.md, "Engagement").

Trials stored before have ``NULL`` (unknown, not zero).

Revision ID: 0014
Revises: 0013
Create Date: 2026-12-07
"""

from __future__ import annotations

import sqlalchemy as sa
from alembic import op

revision = "0014"
down_revision = "0013"
branch_labels = None
depends_on = None

TRIAL_COUNTS = ("task_steps", "robot_task_steps", "stand_ticks")


def upgrade() -> None:
    for name in TRIAL_COUNTS:
        op.add_column("trials", sa.Column(name, sa.Integer(), nullable=True))
    op.add_column("trials", sa.Column("think_seconds", sa.Float(), nullable=True))


def downgrade() -> None:
    with op.batch_alter_table("trials") as batch:
        batch.drop_column("think_seconds")
        for name in reversed(TRIAL_COUNTS):
            batch.drop_column(name)
