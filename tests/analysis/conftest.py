"""Shared data for the analysis tests: a synthetic robot × kitchen long table, and stored studies.

The store fixtures (``db_url`` on SQLite and PostgreSQL, ``study_file``) come from ``tests/conftest.py``, as for
the store tests (in CI they fail instead of skipping when PostgreSQL is unreachable); the running apps
(``make_settings``, ``live_server``) are the server tests' own, loaded from ``tests/server/conftest.py``.
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


@pytest.fixture
def store(db_url: str) -> Iterator[object]:
    """A migrated, empty store on ``db_url``."""
    from store.engine import Store

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
    from store.studies import sync_study
    from study_config.catalog import load_one

    loaded = load_one(study_2x2)
    with store.transaction() as session:  # type: ignore[attr-defined]
        sync_study(session, loaded.study)
    return loaded
