"""A migrated store, a loaded two-condition study, and joins from many threads at once, for the store tests."""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterator

import pytest

from store.engine import Store
from store.studies import sync_study
from study_config.catalog import LoadedStudy, load_one


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


@pytest.fixture
def join_at_once(store: Store, many_connections: None) -> Callable[[LoadedStudy, int], list[int]]:
    """``join_at_once(loaded, n)``: n participants join ``loaded`` from n threads at once; their order indexes
    (fails the test if any join raised)."""
    from server.flow import service

    def run(loaded: LoadedStudy, n: int) -> list[int]:
        results: list[int] = []
        failures: list[BaseException] = []

        def join() -> None:
            try:
                results.append(service.join(store, loaded, {}, False).assignment.order_index)
            except BaseException as exc:
                failures.append(exc)

        threads = [threading.Thread(target=join) for _ in range(n)]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        assert failures == []
        return results

    return run
