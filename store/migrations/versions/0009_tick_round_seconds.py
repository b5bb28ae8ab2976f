"""Ticks record how long their round had run (``round_seconds``, wall-clock seconds while the participant was
connected), so that a round resumed by another process or after a restart keeps its ``timing.max_round_seconds``
instead of starting the limit again.

Ticks stored before have ``NULL``: a round resumed from one of them counts from its resumption, as before.

Revision ID: 0009
Revises: 0008
Create Date: 2026-12-03
"""

from __future__ import annotations

import sqlalchemy as sa
from alembic import op

revision = "0009"
down_revision = "0008"
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.add_column("ticks", sa.Column("round_seconds", sa.Float(), nullable=True))


def downgrade() -> None:
    with op.batch_alter_table("ticks") as batch:
        batch.drop_column("round_seconds")
