"""Trials record the view the participant played in (``top_down`` or ``first_person``).

Revision ID: 0003
Revises: 0002
Create Date: 2026-12-01
"""

from __future__ import annotations

import sqlalchemy as sa
from alembic import op

revision = "0003"
down_revision = "0002"
branch_labels = None
depends_on = None


def upgrade() -> None:
    # Every trial stored before this revision was played top-down (the only view there was).
    op.add_column("trials", sa.Column("view", sa.String(16), nullable=False, server_default="top_down"))


def downgrade() -> None:
    with op.batch_alter_table("trials") as batch:
        batch.drop_column("view")
