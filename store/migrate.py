"""Alembic migrations driven from code (no ``alembic.ini``), so the installed package migrates itself.

``upgrade(engine)`` runs at server start. On PostgreSQL it holds a transaction-level advisory lock, so
several server processes starting together migrate once; on SQLite ``BEGIN IMMEDIATE`` does the same.

For developers: ``python -m store.migrate revision "message"`` autogenerates a new revision
against a scratch SQLite database at head; review it before committing.
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

from alembic import command
from alembic.config import Config
from sqlalchemy import Connection, Engine, create_engine, text
from sqlalchemy.orm import Session

MIGRATIONS = Path(__file__).resolve().parent / "migrations"
ADVISORY_LOCK_KEY = 0x57EA4_0001


def alembic_config() -> Config:
    config = Config()
    config.set_main_option("script_location", str(MIGRATIONS))
    config.set_main_option("path_separator", "os")
    return config


def startup_lock(conn: Connection | Session) -> None:
    """Serialise start-up work (migrations, study rows) between server processes until the transaction
    ends: an advisory lock on PostgreSQL; on SQLite ``BEGIN IMMEDIATE`` already does it."""
    dialect = conn.get_bind().dialect.name if isinstance(conn, Session) else conn.dialect.name
    if dialect == "postgresql":
        conn.execute(text("SELECT pg_advisory_xact_lock(:key)"), {"key": ADVISORY_LOCK_KEY})


def upgrade(engine: Engine, revision: str = "head") -> None:
    """Upgrade the database behind ``engine`` to ``revision`` in one transaction."""
    config = alembic_config()
    with engine.begin() as conn:
        startup_lock(conn)
        config.attributes["connection"] = conn
        command.upgrade(config, revision)


def current_revision(bind: Engine | Connection) -> str | None:
    """The revision the database is at (``None`` before the first migration); on a connection, read in its
    transaction (the analysis reads a whole export on one snapshot)."""
    from alembic.runtime.migration import MigrationContext

    if isinstance(bind, Engine):
        with bind.connect() as conn:
            return current_revision(conn)
    return MigrationContext.configure(bind).get_current_revision()


def head_revision() -> str | None:
    """The newest revision of this version's migrations: the schema it writes and reads."""
    from alembic.script import ScriptDirectory

    return ScriptDirectory.from_config(alembic_config()).get_current_head()


def _revision(message: str) -> None:
    with tempfile.TemporaryDirectory() as folder:
        engine = create_engine(f"sqlite:///{folder}/scratch.sqlite3")
        upgrade(engine)
        config = alembic_config()
        with engine.begin() as conn:
            config.attributes["connection"] = conn
            command.revision(config, message=message, autogenerate=True)
        engine.dispose()


if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] != "revision":
        print("usage: python -m store.migrate revision MESSAGE", file=sys.stderr)
        sys.exit(2)
    _revision(sys.argv[2])
