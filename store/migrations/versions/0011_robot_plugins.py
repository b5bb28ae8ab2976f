"""Trials record the package and version that provided their robot (a plug-in's or this platform's,
``planner.robot_catalog``) and how many of its decisions failed; ticks record why the robot failed there.

Trials stored before have ``NULL`` in all three (their robot was one of the shipped planners of the version then
installed, which was not recorded), and their ticks ``NULL`` for the failure (failures were logged as events only).

Revision ID: 0011
Revises: 0010
Create Date: 2026-12-07
"""

from __future__ import annotations

import sqlalchemy as sa
from alembic import op

revision = "0011"
down_revision = "0010"
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.add_column("trials", sa.Column("failed_decisions", sa.Integer(), nullable=True))
    op.add_column("trials", sa.Column("robot_package", sa.String(length=100), nullable=True))
    op.add_column("trials", sa.Column("robot_version", sa.String(length=64), nullable=True))
    op.add_column("ticks", sa.Column("robot_error", sa.String(length=300), nullable=True))


def downgrade() -> None:
    with op.batch_alter_table("ticks") as batch:
        batch.drop_column("robot_error")
    with op.batch_alter_table("trials") as batch:
        batch.drop_column("robot_version")
        batch.drop_column("robot_package")
        batch.drop_column("failed_decisions")
