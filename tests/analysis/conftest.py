"""Shared data for the analysis tests: a synthetic robot × kitchen long table, and stored studies.

The store fixtures are the server tests' own (``tests/server/conftest.py``: ``db_url`` on SQLite and
PostgreSQL, ``postgres_database``, ``study_file``, ``make_settings``, ``live_server``), loaded from that file so
the analysis tests run on both databases exactly like the store tests (in CI they fail instead of skipping
when PostgreSQL is unreachable).
"""

from __future__ import annotations

import importlib.util
import sys
from collections.abc import Callable, Iterator
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))


def _server_fixtures() -> object:
    spec = importlib.util.spec_from_file_location("steakhouse_server_test_fixtures",
                                                  HERE.parent / "server" / "conftest.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


_server = _server_fixtures()
postgres_database = _server.postgres_database  # type: ignore[attr-defined]
db_url = _server.db_url  # type: ignore[attr-defined]
study_file = _server.study_file  # type: ignore[attr-defined]
make_settings = _server.make_settings  # type: ignore[attr-defined]
live_server = _server.live_server  # type: ignore[attr-defined]

ROBOTS = ("baseline", "fov_aware")
KITCHENS = ("none_3", "mid_2")


def make_cells(n_subjects: int = 12, seed: int = 0) -> pd.DataFrame:
    """One row per participant × robot × kitchen, with two measures and a real robot effect."""
    rng = np.random.default_rng(seed)
    rows = []
    for s in range(1, n_subjects + 1):
        skill = rng.normal(100.0, 15.0)
        for r, robot in enumerate(ROBOTS):
            for k, kitchen in enumerate(KITCHENS):
                rows.append(
                    {
                        "participant": f"P{s:02d}",
                        "robot": robot,
                        "kitchen": kitchen,
                        "ticks": skill - 10.0 * r - 4.0 * r * k + rng.normal(0.0, 4.0),
                        "interrupts": float(rng.poisson(3 + 2 * r)),
                    }
                )
    return pd.DataFrame(rows)


@pytest.fixture
def cells() -> Callable[..., pd.DataFrame]:
    """Factory for the synthetic long table (see ``make_cells``)."""
    return make_cells


@pytest.fixture(scope="module", params=["sqlite", pytest.param("postgresql", marks=pytest.mark.postgres)])
def module_db_url(request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    """Like ``db_url`` but shared by the tests of one module (for stored studies that take seconds to play)."""
    import uuid

    from sqlalchemy import text

    if request.param == "sqlite":
        yield f"sqlite:///{tmp_path_factory.mktemp('store') / 'store.sqlite3'}"
        return
    database = request.getfixturevalue("postgres_database")
    schema = f"m_{uuid.uuid4().hex[:12]}"
    engine = _server._admin_engine(database)  # type: ignore[attr-defined]
    with engine.connect() as conn:
        conn.execute(text(f'CREATE SCHEMA "{schema}"'))
    try:
        yield _server._schema_url(database, schema)  # type: ignore[attr-defined]
    finally:
        with engine.connect() as conn:
            conn.execute(text(f'DROP SCHEMA IF EXISTS "{schema}" CASCADE'))
        engine.dispose()


@pytest.fixture
def store(db_url: str) -> Iterator[object]:
    """A migrated, empty store on ``db_url``."""
    from server.store.engine import Store

    opened = Store(db_url)
    opened.migrate()
    try:
        yield opened
    finally:
        opened.dispose()


@pytest.fixture
def study_2x2(study_file: Callable[..., Path]) -> Path:
    """The study file of :func:`study_overrides` (id ``two_by_two``)."""
    from steakhouse_store_study import study_overrides

    return study_file("two_by_two", **study_overrides())


@pytest.fixture
def loaded_2x2(study_2x2: Path, store: object) -> object:
    """The 2 × 2 study loaded and recorded in ``store``."""
    from server.catalog import load_one
    from server.store.studies import sync_study

    loaded = load_one(study_2x2)
    with store.transaction() as session:  # type: ignore[attr-defined]
        sync_study(session, loaded.study)
    return loaded
