"""Fixtures of the server tests: a store URL on SQLite and on PostgreSQL, test studies, running apps.

PostgreSQL: ``TEST_POSTGRES_URL`` (default ``postgresql+psycopg://postgres@127.0.0.1:5432/test``) names a
server where a fresh database is created for the test session and dropped after it; each test gets its own
schema in it. When ``CI=true`` and the server cannot be reached the tests **fail**; elsewhere they are
skipped with the reason.
"""

from __future__ import annotations

import os
import sys
import uuid
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest
from sqlalchemy import create_engine, text
from sqlalchemy.engine import make_url

sys.path.insert(0, str(Path(__file__).resolve().parent))

from steakhouse_testing import ThreadServer, write_study  # noqa: E402

DEFAULT_PG = "postgresql+psycopg://postgres@127.0.0.1:5432/test"


def _admin_engine(url: str) -> Any:
    return create_engine(url, isolation_level="AUTOCOMMIT", connect_args={"connect_timeout": 3})


@pytest.fixture(scope="session")
def postgres_database() -> Iterator[str]:
    """A fresh PostgreSQL database for this test session (dropped afterwards)."""
    base = os.environ.get("TEST_POSTGRES_URL", DEFAULT_PG)
    try:
        admin = _admin_engine(base)
        with admin.connect() as conn:
            conn.execute(text("SELECT 1"))
    except Exception as exc:  # noqa: BLE001 - any failure means unreachable
        reason = f"PostgreSQL at {make_url(base).render_as_string(hide_password=True)} unreachable: {exc}"
        if os.environ.get("CI", "").lower() == "true":
            pytest.fail(f"CI requires PostgreSQL for the store tests: {reason}")
        pytest.skip(reason)
    name = f"steakhouse_test_{uuid.uuid4().hex[:12]}"
    with admin.connect() as conn:
        conn.execute(text(f'CREATE DATABASE "{name}"'))
    url = make_url(base).set(database=name).render_as_string(hide_password=False)
    try:
        yield url
    finally:
        with admin.connect() as conn:
            conn.execute(text(f'DROP DATABASE IF EXISTS "{name}" WITH (FORCE)'))
        admin.dispose()


def _schema_url(database_url: str, schema: str) -> str:
    return make_url(database_url).update_query_dict({"options": f"-csearch_path={schema}"}).render_as_string(
        hide_password=False)


@pytest.fixture(params=["sqlite", pytest.param("postgresql", marks=pytest.mark.postgres)])
def db_url(request: pytest.FixtureRequest, tmp_path: Path) -> Iterator[str]:
    """A store URL for an empty database: a SQLite file, or a fresh schema on PostgreSQL."""
    if request.param == "sqlite":
        yield f"sqlite:///{tmp_path / 'store.sqlite3'}"
        return
    database = request.getfixturevalue("postgres_database")
    schema = f"t_{uuid.uuid4().hex[:12]}"
    engine = _admin_engine(database)
    with engine.connect() as conn:
        conn.execute(text(f'CREATE SCHEMA "{schema}"'))
    try:
        yield _schema_url(database, schema)
    finally:
        with engine.connect() as conn:
            conn.execute(text(f'DROP SCHEMA IF EXISTS "{schema}" CASCADE'))
        engine.dispose()


@pytest.fixture
def study_file(tmp_path: Path) -> Callable[..., Path]:
    """``study_file(study_id="tiny", **overrides)`` writes a small test study (see ``write_study``)."""
    folder = tmp_path / "studies"
    folder.mkdir(exist_ok=True)
    return lambda study_id="tiny", **overrides: write_study(folder, study_id, **overrides)


@pytest.fixture
def make_settings(db_url: str, tmp_path: Path) -> Callable[..., Any]:
    """Settings for a test app on ``db_url``: in-process robots, fast flushes, a known admin token, no join
    rate limit (tests join many participants from one address; the limit has its own tests)."""
    from server.settings import Settings

    def make(studies: list[Path], **overrides: Any) -> Settings:
        values: dict[str, Any] = {"database_url": db_url, "study_files": tuple(studies), "robot_workers": 0,
                                  "admin_token": "admin-secret", "flush_interval_s": 0.1,
                                  "static_dir": tmp_path / "no-static", "join_rate_per_minute": 0}
        values.update(overrides)
        return Settings(**values)

    return make


@pytest.fixture
def live_server(make_settings: Callable[..., Any]) -> Iterator[Callable[..., ThreadServer]]:
    """``live_server(studies, robot_factory=None, clock=None, **settings)``: a started :class:`ThreadServer`
    (``clock``: the rounds' wall clock, e.g. a ``ManualClock``), stopped at the end of the test."""
    from server.app import create_app

    started: list[ThreadServer] = []

    def start(studies: list[Path], robot_factory: Callable[..., Any] | None = None, clock: Any = None,
              **overrides: Any) -> ThreadServer:
        server = ThreadServer(create_app(make_settings(studies, **overrides), robot_factory=robot_factory,
                                         clock=clock))
        started.append(server.__enter__())
        return server

    yield start
    for server in reversed(started):
        server.__exit__(None, None, None)
