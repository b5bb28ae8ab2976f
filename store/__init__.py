"""The SQL store: SQLAlchemy 2 tables, Alembic migrations and plain functions over a ``Session``.

SQLite by default, PostgreSQL via ``DATABASE_URL``. Every function takes an open ``Session`` (one
transaction) so callers decide transaction boundaries; :class:`Store` owns the engine.
"""

from store.engine import Store

__all__ = ["Store"]
