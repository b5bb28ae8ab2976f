"""Robot health per trial: decisions made, decisions that missed their deadline, and why a trial is invalid.

Revision ID: 0005
Revises: 0004
Create Date: 2026-12-02
"""

from __future__ import annotations

import sqlalchemy as sa
from alembic import op

revision = "0005"
down_revision = "0004"
branch_labels = None
depends_on = None


def upgrade() -> None:
    # Nullable columns without defaults: NULL for trials stored before this revision (unknown, not zero).
    op.add_column("trials", sa.Column("decisions", sa.Integer(), nullable=True))
    op.add_column("trials", sa.Column("missed_decisions", sa.Integer(), nullable=True))
    op.add_column("trials", sa.Column("invalid_reason", sa.String(length=200), nullable=True))


def downgrade() -> None:
    with op.batch_alter_table("trials") as batch:
        batch.drop_column("invalid_reason")
        batch.drop_column("missed_decisions")
        batch.drop_column("decisions")
