"""Ticks keep the world events of their step (who loaded, chopped, washed, plated, delivered, bumped).

Revision ID: 0002
Revises: 0001
Create Date: 2026-11-22
"""

from __future__ import annotations

import sqlalchemy as sa
from alembic import op
from sqlalchemy.dialects import postgresql

revision = "0002"
down_revision = "0001"
branch_labels = None
depends_on = None

JSON = sa.JSON().with_variant(postgresql.JSONB(), "postgresql")


def upgrade() -> None:
    # A nullable column without a default: an in-place ALTER on SQLite and PostgreSQL (no table rewrite).
    op.add_column("ticks", sa.Column("world_events", JSON, nullable=True))


def downgrade() -> None:
    with op.batch_alter_table("ticks") as batch:
        batch.drop_column("world_events")
