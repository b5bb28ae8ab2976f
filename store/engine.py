"""The store's engines and transactions, tuned per database: one set-up for the server's writing engine and the
analysis's reading one.

SQLite (the default) is opened in WAL mode with ``synchronous=NORMAL`` (a committed transaction survives a
killed process), foreign keys on and a 30 s busy timeout; every transaction starts with
``BEGIN IMMEDIATE``, so two writers never interleave a read-then-write (the condition assignment relies on
it) and concurrent writers queue instead of failing. PostgreSQL runs at READ COMMITTED; transactions that
must not interleave take a row lock (``SELECT ... FOR UPDATE``, see :mod:`store.assignment`).

A store is read (the analysis's export, ``analysis/source/store_reader.py``) while a server may keep writing to it, so
:func:`snapshot_engine` gives engines whose transactions are snapshots: SQLite starts them with a deferred
``BEGIN`` (in WAL mode it reads one version of the file and takes no write lock), PostgreSQL runs them at
REPEATABLE READ. Reading never creates a database: a SQLite file that does not exist is an error.
"""

from __future__ import annotations

import logging
import sqlite3
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from sqlalchemy import Engine, create_engine, event, text
from sqlalchemy.engine import make_url
from sqlalchemy.orm import Session, sessionmaker
from sqlalchemy.pool import QueuePool

SQLITE_BUSY_MS = 30_000
DRAIN_S = 10.0
"""How long closing a store waits for its connections in use to come back."""
log = logging.getLogger(__name__)


class Store:
    """Owns the engine; :meth:`transaction` gives a ``Session`` that commits on success."""

    def __init__(self, url: str) -> None:
        self.url = make_url(url)
        self.engine = _create_engine(url)
        self._sessions = sessionmaker(self.engine, expire_on_commit=False)

    @property
    def dialect(self) -> str:
        return self.engine.dialect.name

    @contextmanager
    def transaction(self) -> Iterator[Session]:
        """One transaction: committed when the block ends normally, rolled back on an exception."""
        with self._sessions.begin() as session:
            yield session

    def ping(self) -> bool:
        """Whether the database answers a trivial query."""
        try:
            with self.engine.connect() as conn:
                conn.execute(text("SELECT 1"))
                conn.rollback()
            return True
        except Exception:  # any failure means "not healthy"
            return False

    def migrate(self) -> None:
        """Bring the schema to the newest Alembic revision (safe to call from several processes)."""
        from store.migrate import upgrade

        upgrade(self.engine)

    def dispose(self, drain_s: float = DRAIN_S) -> None:
        """Close the store's connections, once those in use elsewhere (a read in another thread, a last write)
        are back, waiting at most ``drain_s``. A connection in use when the engine is disposed goes back to a pool
        nobody holds any more and stays open until the garbage collector finds it."""
        pool = self.engine.pool
        deadline = time.monotonic() + drain_s
        while isinstance(pool, QueuePool) and pool.checkedout() > 0:
            if time.monotonic() >= deadline:
                log.warning("closing the store with %d connection(s) still in use after %.0f s",
                            pool.checkedout(), drain_s)
                break
            time.sleep(0.01)
        self.engine.dispose()


class NoStoreError(FileNotFoundError):
    """A store to be read does not exist (reading never creates one)."""


def snapshot_engine(url: str) -> Engine:
    """An engine for reading the store at ``url`` while others may write to it: each transaction reads one
    snapshot (see the module's docstring). Raises :class:`NoStoreError` for a SQLite file that does not exist."""
    parsed = make_url(url)
    if parsed.get_backend_name() != "sqlite":
        return create_engine(url, isolation_level="REPEATABLE READ")
    database = parsed.database or ""
    if not database or database == ":memory:" or not Path(database).expanduser().is_file():
        raise NoStoreError(f"no store at {url}: the SQLite file does not exist")
    engine = create_engine(url, connect_args=_SQLITE_ARGS)
    event.listen(engine, "connect", _sqlite_session)
    event.listen(engine, "begin", _sqlite_begin_snapshot)
    return engine


_SQLITE_ARGS = {"timeout": SQLITE_BUSY_MS / 1000, "check_same_thread": False}


def _create_engine(url: str) -> Engine:
    parsed = make_url(url)
    if parsed.get_backend_name() == "sqlite":
        database = parsed.database or ""
        if not database or database == ":memory:":
            raise ValueError("the SQLite store needs a file (sqlite:///path/to/file.sqlite3)")
        Path(database).expanduser().resolve().parent.mkdir(parents=True, exist_ok=True)
        engine = create_engine(url, pool_size=10, max_overflow=30, pool_timeout=60, connect_args=_SQLITE_ARGS)
        event.listen(engine, "connect", _sqlite_connect)
        event.listen(engine, "begin", _sqlite_begin)
        return engine
    return create_engine(url, pool_size=10, max_overflow=30, pool_timeout=60, pool_pre_ping=True)


def _sqlite_session(dbapi_connection: Any, _record: Any) -> None:
    """Every SQLite connection: transactions begun by the engine's ``begin`` hook (not by the driver), and the
    busy timeout."""
    dbapi_connection.isolation_level = None
    cursor = dbapi_connection.cursor()
    cursor.execute(f"PRAGMA busy_timeout={SQLITE_BUSY_MS}")
    cursor.close()


def _sqlite_connect(dbapi_connection: Any, record: Any) -> None:
    """A writing connection: also WAL, ``synchronous=NORMAL`` and foreign keys."""
    _sqlite_session(dbapi_connection, record)
    cursor = dbapi_connection.cursor()
    _enable_wal(cursor)
    for pragma in ("synchronous=NORMAL", "foreign_keys=ON"):
        cursor.execute(f"PRAGMA {pragma}")
    cursor.close()


def _enable_wal(cursor: Any) -> None:
    """Put the file in WAL mode. Switching the journal mode of a new file takes an exclusive lock that SQLite
    does not wait for through the busy handler: when several connections (server processes starting together)
    open a new file at once, the others get "database is locked" until the first one's switch is done, so they
    try again until then (within the busy timeout)."""
    deadline = time.monotonic() + SQLITE_BUSY_MS / 1000
    while True:
        try:
            cursor.execute("PRAGMA journal_mode=WAL")
            return
        except sqlite3.OperationalError as exc:
            if "locked" not in str(exc) or time.monotonic() > deadline:
                raise
            time.sleep(0.01)


def _sqlite_begin(conn: Any) -> None:
    conn.exec_driver_sql("BEGIN IMMEDIATE")


def _sqlite_begin_snapshot(conn: Any) -> None:
    conn.exec_driver_sql("BEGIN")
