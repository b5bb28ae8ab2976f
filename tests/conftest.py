"""Shared fixtures: small hand-made kitchens for rule tests, a store URL on SQLite and on PostgreSQL, test studies.

PostgreSQL: ``TEST_POSTGRES_URL`` (default ``postgresql+psycopg://postgres@127.0.0.1:5432/test``) names a
server where a fresh database is created for the test session and dropped after it; each test gets its own
schema in it. When ``CI=true`` and the server cannot be reached the tests **fail**; elsewhere they are
skipped with the reason.

SQLite: a test's store is a copy of one migrated once per session (``sqlite_template``): running the nine
migrations took 0.1 s a test. (On PostgreSQL a database copied from a migrated template was no faster than a
fresh schema migrated by the test: measured over ``tests/store`` and ``tests/server/routes``.)
"""

from __future__ import annotations

import asyncio
import contextlib
import fcntl
import os
import shutil
import sys
import uuid
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest
from sqlalchemy import create_engine, text
from sqlalchemy.engine import make_url

from planner.layout import Layout, parse_layout

sys.path.insert(0, str(Path(__file__).resolve().parent / "server"))

from steakhouse_testing import write_study

PLUGINS = Path(__file__).resolve().parent / "plugins"
"""Robot plug-ins that fail in each way (``tests/plugins/steakhouse_broken_robots``), registered by a dist-info beside
them: found on ``sys.path``, never installed."""
EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "mylab_robots"
"""The example plug-in package (docs/robots.md), installed into the test environment by ``make test``."""

# Stations along the top wall (x = 1..7: onion, meat, plate, grill, board, sink, serve), a counter island
# at (4, 3) reachable from both sides, the robot starting at (1, 3), the human at (7, 3).
RULES_KITCHEN = """\
XXXXXXXXX
XOMDPBWSX
X       X
X1  X  2X
X       X
XXXXXXXXX
"""


@pytest.hookimpl(trylast=True)
def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """Modules with a test marked ``slow`` run first, each module's tests kept together and in pytest's order.

    With ``--dist worksteal`` (the Makefile) each worker starts on one contiguous share of this order and an idle
    worker takes the tail of another's queue, so the long tests start early and the last ones to run are short:
    the workers finish together. (In collection order the mypy check ran last, alone, for over a minute.)"""
    def module_of(item: pytest.Item) -> str:
        return item.nodeid.split("::", 1)[0]

    slow = {module_of(item) for item in items if item.get_closest_marker("slow") is not None}
    items.sort(key=lambda item: module_of(item) not in slow)  # stable: the order within each group is kept


@pytest.fixture(autouse=True)
def _playwright_loop_set_aside(request: pytest.FixtureRequest) -> Iterator[None]:
    """Playwright's sync driver lives for the whole session on a worker (``tests/static/conftest.py``), and between
    browser calls its event loop stays marked as running in the worker's thread: a later test on that worker that
    calls ``asyncio.run()`` would fail with "cannot be called from a running event loop", depending only on which
    tests the worker happened to run before. A test that does not use the browser runs with that loop set aside,
    and gets it back afterwards for the next browser test."""
    loop = asyncio._get_running_loop()
    if loop is None or "playwright_driver" in request.fixturenames:
        yield
        return
    asyncio._set_running_loop(None)
    try:
        yield
    finally:
        asyncio._set_running_loop(loop)


@pytest.fixture
def broken_robots(monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    """The broken plug-ins (:data:`PLUGINS`) installed for one test: on ``sys.path`` (robot worker processes started
    meanwhile inherit it) and discovered afresh."""
    from planner import robot_catalog

    monkeypatch.syspath_prepend(str(PLUGINS))
    robot_catalog.forget()
    yield
    robot_catalog.forget()


@pytest.fixture(scope="session")
def example_robots() -> None:
    """The example plug-in package (:data:`EXAMPLE`) installed in the test environment. ``make test`` installs it
    (``make examples``); a test session started otherwise installs it here, once (pip, editable, without
    dependencies), and makes it importable in this process too (its ``.pth`` is read only at interpreter start)."""
    import fcntl
    import importlib
    import subprocess
    from importlib import metadata

    from planner import robot_catalog

    with open(Path(sys.prefix) / ".steakhouse-examples.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            metadata.distribution("mylab-robots")
        except metadata.PackageNotFoundError:
            subprocess.run([sys.executable, "-m", "pip", "install", "-q", "--no-deps", "-e", str(EXAMPLE)],
                           check=True)
            importlib.invalidate_caches()
    if str(EXAMPLE) not in sys.path:
        sys.path.append(str(EXAMPLE))
    robot_catalog.forget()


@pytest.fixture(scope="session")
def kitchen() -> Layout:
    return parse_layout(RULES_KITCHEN, name="rules_kitchen")


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
    except Exception as exc:  # any failure means unreachable
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


@pytest.fixture(scope="session")
def sqlite_template(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A SQLite store migrated to the newest revision (and closed: one file), copied for each ``db_url``."""
    from store.engine import Store

    path = tmp_path_factory.mktemp("template") / "store.sqlite3"
    store = Store(f"sqlite:///{path}")
    try:
        store.migrate()
    finally:
        store.dispose()
    leftovers = [p.name for p in path.parent.iterdir() if p != path]
    assert leftovers == [], f"the template store is not one closed file: {leftovers}"
    return path


@contextlib.contextmanager
def _fresh_store_url(request: pytest.FixtureRequest, sqlite_dir: Path, prefix: str,
                     migrated: bool = True) -> Iterator[str]:
    """A SQLite file in ``sqlite_dir`` (``migrated``: a copy of ``sqlite_template``, else no file yet), or a fresh
    schema (dropped afterwards) in the session's PostgreSQL database, as ``request.param`` says."""
    if request.param == "sqlite":
        path = sqlite_dir / "store.sqlite3"
        if migrated:
            shutil.copyfile(request.getfixturevalue("sqlite_template"), path)
        yield f"sqlite:///{path}"
        return
    database = request.getfixturevalue("postgres_database")
    schema = f"{prefix}_{uuid.uuid4().hex[:12]}"
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
def many_connections(tmp_path_factory: pytest.TempPathFactory) -> Iterator[None]:
    """Held by a test that opens tens of database connections at once (joins from 41 threads, two server processes
    with pools of up to 40 each): such tests run one at a time across the workers, waiting on a lock file shared by
    them, since two at once could pass PostgreSQL's connection limit (100 by default) and fail each other with "too
    many clients"."""
    lock = tmp_path_factory.getbasetemp().parent / "many_connections.lock"
    with lock.open("a") as handle:
        fcntl.flock(handle, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(handle, fcntl.LOCK_UN)


STORES = ["sqlite", pytest.param("postgresql", marks=pytest.mark.postgres)]


@pytest.hookimpl(tryfirst=True)
def pytest_generate_tests(metafunc: pytest.Metafunc) -> None:
    """A test marked ``store_agnostic`` gets its store on SQLite only. The rest run on both stores: the store's
    own tests, and every test whose outcome the database could change (queries, constraints, locks between
    requests and processes, restarts and resumption, assignment, exports). A store-agnostic test checks the
    protocol, the game's rules or what a participant is sent, which the store only records (docs/testing.md).
    The store is given as a ``parametrize`` mark, which pytest applies instead of the fixture's own params."""
    if metafunc.definition.get_closest_marker("store_agnostic") is None:
        return
    for name in ("db_url", "module_db_url"):
        if name in metafunc.fixturenames:
            metafunc.definition.add_marker(pytest.mark.parametrize(name, ["sqlite"], indirect=True))


@pytest.fixture(params=STORES)
def db_url(request: pytest.FixtureRequest, tmp_path: Path) -> Iterator[str]:
    """A store URL for an empty store, to be migrated before use (``Store.migrate()``, or the app at its start): a
    SQLite file already at the newest migration (so migrating it does nothing), or a fresh schema on PostgreSQL."""
    with _fresh_store_url(request, tmp_path, "t") as url:
        yield url


@pytest.fixture(params=STORES)
def empty_db_url(request: pytest.FixtureRequest, tmp_path: Path) -> Iterator[str]:
    """A store URL for an empty database that no migration has touched, for the migration tests: a new SQLite
    file, or a fresh schema on PostgreSQL."""
    with _fresh_store_url(request, tmp_path, "e", migrated=False) as url:
        yield url


@pytest.fixture(scope="module", params=STORES)
def module_db_url(request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    """Like ``db_url`` but shared by the tests of one module (for stored studies that take seconds to play)."""
    with _fresh_store_url(request, tmp_path_factory.mktemp("store"), "m") as url:
        yield url


@pytest.fixture
def study_file(tmp_path: Path) -> Callable[..., Path]:
    """``study_file(study_id="tiny", **overrides)`` writes a small test study (see ``write_study``)."""
    folder = tmp_path / "studies"
    folder.mkdir(exist_ok=True)
    return lambda study_id="tiny", **overrides: write_study(folder, study_id, **overrides)
