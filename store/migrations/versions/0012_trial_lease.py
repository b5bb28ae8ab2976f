"""One owner per live round: a lease with a fencing number on the trial row, and the round's clock kept with it.

- ``trials.lease_epoch`` grows by one at every takeover (a server process starting or resuming the round);
  ``lease_owner`` (``host:pid``) and ``lease_until`` say who holds it and until when (renewed at every store
  flush). Every tick and trial event carries the epoch it was made under (``ticks.epoch``, ``events.epoch``);
  the store refuses rows and ends from an older one (``store/lease.py``).
- The crash-aware clock of a round, renewed with the lease: ``away_since`` (the participant's connection
  dropped then; NULL while connected), ``connected_s`` (seconds the round has run while connected) and
  ``open_wait_s`` (seconds of the wait for the participant running then, NULL when none).

Rows stored before have epoch 0 (trials) or NULL (ticks, events) and no lease: they are judged as before.

Revision ID: 0012
Revises: 0011
Create Date: 2026-12-07
"""

from __future__ import annotations

import sqlalchemy as sa
from alembic import op

revision = "0012"
down_revision = "0011"
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.add_column("trials", sa.Column("lease_epoch", sa.Integer(), nullable=False, server_default="0"))
    op.add_column("trials", sa.Column("lease_owner", sa.String(length=128), nullable=True))
    op.add_column("trials", sa.Column("lease_until", sa.DateTime(timezone=True), nullable=True))
    op.add_column("trials", sa.Column("away_since", sa.DateTime(timezone=True), nullable=True))
    op.add_column("trials", sa.Column("connected_s", sa.Float(), nullable=True))
    op.add_column("trials", sa.Column("open_wait_s", sa.Float(), nullable=True))
    op.add_column("ticks", sa.Column("epoch", sa.Integer(), nullable=True))
    op.add_column("events", sa.Column("epoch", sa.Integer(), nullable=True))


def downgrade() -> None:
    with op.batch_alter_table("events") as batch:
        batch.drop_column("epoch")
    with op.batch_alter_table("ticks") as batch:
        batch.drop_column("epoch")
    with op.batch_alter_table("trials") as batch:
        for name in ("open_wait_s", "connected_s", "away_since", "lease_until", "lease_owner", "lease_epoch"):
            batch.drop_column(name)
