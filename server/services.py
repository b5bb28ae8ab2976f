"""Everything the routes need, created once by the app's lifespan and kept in ``app.state.services``."""

from __future__ import annotations

from dataclasses import dataclass

from server.game.registry import GameRegistry
from server.robots import RobotPool
from server.settings import Settings
from store.engine import Store
from store.writer import BatchWriter
from study_config.catalog import Catalog


@dataclass(frozen=True)
class Services:
    settings: Settings
    catalog: Catalog
    store: Store
    writer: BatchWriter
    pool: RobotPool
    registry: GameRegistry
    admin_token: str
