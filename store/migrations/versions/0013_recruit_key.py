"""Recruiting ids are compared by a key that look-alikes share (``store/recruit_ids.py``: NFKC, no combining marks,
the Unicode TR39 confusable skeleton with case folded), kept in ``participants.recruit_key`` (unique per study);
``recruit_id`` keeps the id as given.

Participants stored before held their id trimmed and in lower case: their id as given is taken back from their
``recruiting`` parameters where one of them matches, and their key computed from it. Where two participants of a
study already share a key (a look-alike re-enrolment), the older keeps it and the later ones get none (their
sessions go on with their tokens; a new browser with the id meets the older one).

Revision ID: 0013
Revises: 0012
Create Date: 2026-12-07
"""

from __future__ import annotations

import logging

import sqlalchemy as sa
from alembic import op

from store.recruit_ids import recruit_key

revision = "0013"
down_revision = "0012"
branch_labels = None
depends_on = None

log = logging.getLogger("alembic.runtime.migration")
_PARTICIPANTS = sa.table("participants", sa.column("id", sa.Integer()), sa.column("study_id", sa.String()),
                         sa.column("recruit_id", sa.String()), sa.column("recruit_key", sa.String()),
                         sa.column("recruiting", sa.JSON()))


def upgrade() -> None:
    op.add_column("participants", sa.Column("recruit_key", sa.String(length=200), nullable=True))
    conn = op.get_bind()
    taken: set[tuple[str, str]] = set()
    rows = conn.execute(sa.select(_PARTICIPANTS.c.id, _PARTICIPANTS.c.study_id, _PARTICIPANTS.c.recruit_id,
                                  _PARTICIPANTS.c.recruiting).where(_PARTICIPANTS.c.recruit_id.is_not(None))
                        .order_by(_PARTICIPANTS.c.id)).all()
    for participant_id, study_id, stored, recruiting in rows:
        given = next((v for v in (recruiting or {}).values()
                      if isinstance(v, str) and v.strip().lower() == stored), stored)
        key = recruit_key(given)
        if key is not None and (study_id, key) in taken:
            log.warning("participant %d of study %s has a look-alike of an older participant's recruiting id: "
                        "it keeps no key", participant_id, study_id)
            key = None
        if key is not None:
            taken.add((study_id, key))
        conn.execute(_PARTICIPANTS.update().where(_PARTICIPANTS.c.id == participant_id)
                     .values(recruit_id=given[:200], recruit_key=key))
    # A unique index rather than a constraint: SQLite adds one without rebuilding the table (which its foreign keys
    # forbid inside the migration's transaction). The old constraint on (study_id, recruit_id) stays: ids as given
    # that share no key are distinct anyway.
    op.create_index("uq_participants_study_recruit_key", "participants", ["study_id", "recruit_key"], unique=True)


def downgrade() -> None:
    op.drop_index("uq_participants_study_recruit_key", table_name="participants")
    op.drop_column("participants", "recruit_key")  # in place (SQLite 3.35+), as the column is in no constraint
