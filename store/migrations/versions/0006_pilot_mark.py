"""Pilot participants: the mark of a simulated participant run by ``steakhouse pilot`` (docs/admin.md).

Revision ID: 0006
Revises: 0005
Create Date: 2026-12-02
"""

from __future__ import annotations

import sqlalchemy as sa
from alembic import op

revision = "0006"
down_revision = "0005"
branch_labels = None
depends_on = None


def upgrade() -> None:
    # A NOT NULL column with a server default: SQLite and PostgreSQL fill existing rows in place.
    op.add_column("participants", sa.Column("pilot", sa.Boolean(), nullable=False, server_default=sa.false()))
    op.add_column("participants", sa.Column("pilot_pace", sa.String(16), nullable=True))


def downgrade() -> None:
    with op.batch_alter_table("participants") as batch:
        batch.drop_column("pilot_pace")
        batch.drop_column("pilot")
