"""Ticks keep the reference's KB gap of their step (``kb_diff``: per component, as the paper's code measures it,
docs/domain.md §6), beside our older status gap (``kb_gap``).

Ticks stored before have ``NULL``: the analysis computes theirs from the stored world and KB states.

Revision ID: 0010
Revises: 0009
Create Date: 2026-12-07
"""

from __future__ import annotations

import sqlalchemy as sa
from alembic import op
from sqlalchemy.dialects import postgresql

revision = "0010"
down_revision = "0009"
branch_labels = None
depends_on = None

JSON = sa.JSON().with_variant(postgresql.JSONB(), "postgresql")


def upgrade() -> None:
    # A nullable column without a default: an in-place ALTER on SQLite and PostgreSQL (no table rewrite).
    op.add_column("ticks", sa.Column("kb_diff", JSON, nullable=True))


def downgrade() -> None:
    with op.batch_alter_table("ticks") as batch:
        batch.drop_column("kb_diff")
