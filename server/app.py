"""The FastAPI application: ``create_app(settings)``.

Studies are loaded and validated when the app is created (an invalid study raises before anything
starts). At start-up the lifespan opens the store and migrates it, records the studies, starts the
background writer, the robot worker pool and the game registry, and puts them in ``app.state.services``;
at shutdown it suspends the live trials (they resume from the store), flushes the writer and stops the
workers. No module-level mutable state.
"""

from __future__ import annotations

import asyncio
import logging
import secrets
from collections.abc import AsyncIterator
from contextlib import AsyncExitStack, asynccontextmanager

from fastapi import FastAPI

from planner.robot_catalog import RobotFactory
from server import errors, security
from server.game.admission import Admission
from server.game.clock import Clock, MonotonicClock
from server.game.live import GameDeps
from server.game.lobby import Lobby
from server.game.registry import GameRegistry
from server.robots import make_pool
from server.routes import admin, admin_exports, health, participant, play
from server.routes.static import client_files
from server.services import Services
from server.settings import Settings
from store.engine import Store
from store.migrate import startup_lock
from store.studies import sync_study
from store.writer import BatchWriter
from study_config.catalog import Catalog, load_catalog

log = logging.getLogger("server")


def create_app(settings: Settings | None = None, *, robot_factory: RobotFactory | None = None,
               clock: Clock | None = None) -> FastAPI:
    """The app for ``settings`` (read from the environment when omitted).

    ``robot_factory`` replaces ``settings.robot_factory`` for in-process planners (``robot_workers = 0``);
    ``clock`` replaces the wall clock of the rounds' limit and idle nudge (tests move it by hand).
    """
    settings = settings or Settings()
    catalog = load_catalog(settings.study_files)
    admin_token = _admin_token(settings)

    @asynccontextmanager
    async def lifespan(app: FastAPI) -> AsyncIterator[None]:
        # Each part is closed when the app stops, in the reverse order of opening, even when opening a later part
        # or closing an earlier one fails (a store left open would hold its database connections).
        async with AsyncExitStack() as opened:
            store = Store(settings.database_url)
            opened.callback(store.dispose)
            await asyncio.to_thread(_prepare_store, store, catalog)
            writer = BatchWriter(store, settings.flush_interval_s)
            writer.start()
            opened.push_async_callback(writer.close)
            pool = make_pool(settings.workers, settings.robot_factory, robot_factory)
            await pool.start()
            opened.push_async_callback(pool.shutdown)
            deps = GameDeps(store, writer, pool, settings.decision_deadline_fraction, settings.max_message_bytes,
                            on_end=lambda game: None, clock=clock or MonotonicClock())
            lobby = Lobby(catalog, store, writer, Admission(settings.live_trial_capacity),
                          settings.admission_max_wait_s)
            registry = GameRegistry(catalog, deps, settings.sweep_interval_s, lobby)
            await registry.start()
            opened.push_async_callback(registry.shutdown)
            app.state.services = Services(settings, catalog, store, writer, pool, registry, admin_token)
            log.info("serving %s on %s with %s robot worker(s), at most %d live trial(s)",
                     ", ".join(catalog.studies), store.dialect, settings.workers or "in-process",
                     settings.live_trial_capacity)
            yield

    app = FastAPI(title="Steakhouse Study", version="0.1.0", lifespan=lifespan)
    app.state.catalog = catalog
    app.state.admin_token = admin_token
    errors.install(app)
    security.install(app, settings.join_rate_per_minute, settings.max_body_bytes)
    for module in (health, participant, play, admin, admin_exports):
        app.include_router(module.router)
    static = settings.static_root()
    if static is not None:
        app.mount("/", client_files(static), name="client")
    return app


def _prepare_store(store: Store, catalog: Catalog) -> None:
    store.migrate()
    with store.transaction() as session:
        startup_lock(session)
        for loaded in catalog:
            sync_study(session, loaded.study)


def _admin_token(settings: Settings) -> str:
    if settings.admin_token is not None and settings.admin_token.get_secret_value():
        return settings.admin_token.get_secret_value()
    token = secrets.token_urlsafe(24)
    log.warning("no STEAKHOUSE_ADMIN_TOKEN set; the admin token for this run is: %s", token)
    return token
