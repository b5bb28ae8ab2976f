"""Closing a store closes every connection it opened, those in use in another thread at that moment included."""

from __future__ import annotations

import sqlite3
import threading
from typing import Any

import pytest
from sqlalchemy import text

from store.engine import Store


def closed(raw: Any) -> bool:
    """Whether a DBAPI connection (psycopg or sqlite3) is closed."""
    if isinstance(raw, sqlite3.Connection):
        try:
            raw.execute("SELECT 1")
        except sqlite3.ProgrammingError:
            return True
        return False
    return bool(raw.closed)


def test_closing_a_store_waits_for_a_connection_in_use_and_closes_it(db_url: str) -> None:
    """A read still running in another thread when the server stops: closing the store waits for it to give its
    connection back and then closes it (before, that connection went back to a pool nobody held and stayed open
    until the garbage collector found it, which a test running at that moment saw as a ResourceWarning)."""
    store = Store(db_url)
    opened, release = threading.Event(), threading.Event()
    raws: list[Any] = []

    def read() -> None:
        with store.engine.connect() as conn:
            conn.execute(text("SELECT 1"))
            raws.append(conn.connection.dbapi_connection)
            opened.set()
            release.wait()

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    try:
        assert opened.wait(30)
        closing = threading.Thread(target=store.dispose)
        closing.start()
        closing.join(0.2)
        assert closing.is_alive(), "it waits while the connection is in use"
    finally:
        release.set()
    reader.join()
    closing.join()
    assert closed(raws[0]), "the connection is closed once given back"


def test_a_connection_never_given_back_does_not_keep_the_store_open(db_url: str,
                                                                    caplog: pytest.LogCaptureFixture) -> None:
    """A connection held past the wait: the store closes anyway, and the log says how many were still in use."""
    store = Store(db_url)
    conn = store.engine.connect()
    raw = conn.connection.dbapi_connection
    assert raw is not None
    try:
        with caplog.at_level("WARNING", logger="store.engine"):
            store.dispose(drain_s=0.05)
        assert "1 connection(s) still in use" in caplog.text
    finally:
        conn.close()
        raw.close()  # it went back to the pool that closing the store let go of
