"""A migrated store and a loaded two-condition study for the store tests."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from server.catalog import LoadedStudy, load_one
from server.store.engine import Store
from server.store.studies import sync_study


@pytest.fixture
def store(db_url: str) -> Iterator[Store]:
    store = Store(db_url)
    store.migrate()
    try:
        yield store
    finally:
        store.dispose()


@pytest.fixture
def loaded(study_file, store: Store) -> LoadedStudy:
    """Two conditions (stay and fov_aware in the practice kitchen), so two condition orders."""
    loaded = load_one(study_file(robots=["stay", "fov_aware"]))
    with store.transaction() as session:
        sync_study(session, loaded.study)
    return loaded
