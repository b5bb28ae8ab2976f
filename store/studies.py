"""Study rows: one per study id served, refreshed from the study files at every start."""

from __future__ import annotations

import json

from sqlalchemy.orm import Session

from store.tables import StudyRow
from store.types import utcnow
from study_config.study import Study


def sync_study(session: Session, study: Study) -> StudyRow:
    """Insert or update the row of ``study`` (title, resolved config, hash, condition orders).

    Participants keep the order and plan they were given; trials keep the config hash they ran under.
    """
    row = session.get(StudyRow, study.id)
    config = json.loads(study.canonical_json())
    config_hash = study.config_hash()
    orders = [list(order) for order in study.condition_orders()]
    now = utcnow()
    if row is None:
        row = StudyRow(id=study.id, title=study.title, config_hash=config_hash, config=config,
                       orders=orders, created_at=now, updated_at=now)
        session.add(row)
    elif row.config_hash != config_hash or row.title != study.title:
        row.title, row.config_hash, row.config, row.orders, row.updated_at = (
            study.title, config_hash, config, orders, now)
    session.flush()
    return row
