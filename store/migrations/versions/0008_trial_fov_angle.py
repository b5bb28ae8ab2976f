"""Trials record the participant's field of view (``fov_angle``, a study factor since this revision).

Trials stored before were played at their study's one ``world.fov_angle``. Where the study's stored configuration
is the one a trial was played with (same config hash), that angle is filled in; other trials keep ``NULL``
(their angle is not in the store).

Revision ID: 0008
Revises: 0007
Create Date: 2026-12-03
"""

from __future__ import annotations

import sqlalchemy as sa
from alembic import op

from planner.perception import FOV_ANGLE

revision = "0008"
down_revision = "0007"
branch_labels = None
depends_on = None

_STUDIES = sa.table("studies", sa.column("id", sa.String()), sa.column("config_hash", sa.String()),
                    sa.column("config", sa.JSON()))
_TRIALS = sa.table("trials", sa.column("study_id", sa.String()), sa.column("config_hash", sa.String()),
                   sa.column("fov_angle", sa.Float()))


def upgrade() -> None:
    op.add_column("trials", sa.Column("fov_angle", sa.Float(), nullable=True))
    conn = op.get_bind()
    for study_id, config_hash, config in conn.execute(sa.select(_STUDIES.c.id, _STUDIES.c.config_hash,
                                                                _STUDIES.c.config)).all():
        world = (config or {}).get("world") or {}
        conn.execute(_TRIALS.update()
                     .where(_TRIALS.c.study_id == study_id, _TRIALS.c.config_hash == config_hash)
                     .values(fov_angle=float(world.get("fov_angle", FOV_ANGLE))))


def downgrade() -> None:
    with op.batch_alter_table("trials") as batch:
        batch.drop_column("fov_angle")
