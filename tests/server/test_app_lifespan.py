"""The app's start and stop (``server/app.py``): whatever fails while the app opens its parts or closes them,
the parts already open are closed, the store's database connections first among them."""

from __future__ import annotations

import asyncio
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

pytestmark = pytest.mark.store_agnostic


class Broke(RuntimeError):
    pass


@pytest.fixture
def disposed(monkeypatch: pytest.MonkeyPatch) -> list[object]:
    """The stores disposed in this test, in order."""
    from store.engine import Store

    calls: list[object] = []
    dispose = Store.dispose

    def record(store: Store) -> None:
        calls.append(store)
        dispose(store)

    monkeypatch.setattr(Store, "dispose", record)
    return calls


def _app(make_settings: Callable[..., Any], study_file: Callable[..., Path]) -> Any:
    from server.app import create_app

    return create_app(make_settings([study_file("tiny")]))


def run(app: Any, while_up: Callable[[Any], None] = lambda services: None) -> None:
    """Start ``app`` (its lifespan, as a server does), call ``while_up`` with its services, stop it."""

    async def up_and_down() -> None:
        async with app.router.lifespan_context(app):
            while_up(app.state.services)

    asyncio.run(up_and_down())


def test_a_start_that_fails_after_the_store_opened_closes_the_store(
        make_settings, study_file, disposed, monkeypatch) -> None:
    from server.game.registry import GameRegistry

    async def broken_start(self: GameRegistry) -> None:
        raise Broke("the registry cannot start")

    monkeypatch.setattr(GameRegistry, "start", broken_start)
    with pytest.raises(Broke):
        run(_app(make_settings, study_file))
    assert len(disposed) == 1


def test_a_stop_that_fails_part_way_still_flushes_the_writer_and_closes_the_store(
        make_settings, study_file, disposed, monkeypatch) -> None:
    from server.game.registry import GameRegistry
    from store.writer import BatchWriter

    closed: list[BatchWriter] = []
    close = BatchWriter.close

    async def broken_shutdown(self: GameRegistry) -> None:
        raise Broke("the registry cannot stop")

    async def recorded_close(self: BatchWriter) -> None:
        closed.append(self)
        await close(self)

    monkeypatch.setattr(GameRegistry, "shutdown", broken_shutdown)
    monkeypatch.setattr(BatchWriter, "close", recorded_close)
    app = _app(make_settings, study_file)
    with pytest.raises(Broke):
        run(app, lambda services: services.store.ping() or pytest.fail("the store did not answer"))
    assert closed == [app.state.services.writer]
    assert disposed == [app.state.services.store]


def test_a_clean_stop_closes_every_part_once(make_settings, study_file, disposed) -> None:
    app = _app(make_settings, study_file)
    run(app, lambda services: services.store.ping() or pytest.fail("the store did not answer"))
    assert disposed == [app.state.services.store]
    assert app.state.services.store.engine.pool.checkedout() == 0
