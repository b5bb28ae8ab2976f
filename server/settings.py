"""Server settings, read once at start-up from the environment (prefix ``STEAKHOUSE_``) and validated.

``DATABASE_URL`` is honoured as well as ``STEAKHOUSE_DATABASE_URL`` (the usual name on hosting platforms).
A ``postgres://`` or ``postgresql://`` URL is read as PostgreSQL through psycopg 3. Relative SQLite paths are
relative to the working directory; the file's folder is created when the store opens.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Literal

from pydantic import AliasChoices, Field, SecretStr, field_validator
from pydantic_settings import BaseSettings, SettingsConfigDict

from server.game.admission import DEFAULT_MAX_WAIT_S, default_capacity
from study_config import STUDY_DIR

DEFAULT_DATABASE_URL = "sqlite:///./data/steakhouse.sqlite3"
DEFAULT_STUDIES = (STUDY_DIR / "demo.yaml", STUDY_DIR / "demo_first_person.yaml", STUDY_DIR / "paper_study.yaml")
_REPO_STATIC = Path(__file__).resolve().parents[1] / "static"
WORKERS_PER_CORE = 2
"""Robot workers per CPU. A worker serves its trials' decisions one at a time, so one slow decision holds up
every other trial pinned to it; with twice as many workers as cores the operating system shares the cores
between them and a slow decision holds up half as many trials. At 60 trials on 2 cores, ``capacity.py
--counts 60 --all`` passed 7 of 7 runs with 4 workers and 10 of 12 with 2 (docs/operations.md §2); each worker
costs ~70 MB."""


def default_workers() -> int:
    """Robot worker processes when ``robot_workers`` is not set: ``WORKERS_PER_CORE`` per CPU."""
    return WORKERS_PER_CORE * (os.cpu_count() or 1)


class Settings(BaseSettings):
    """Everything the server needs to start; invalid values stop it with a clear message."""

    model_config = SettingsConfigDict(env_prefix="STEAKHOUSE_", extra="ignore", frozen=True)

    host: str = "127.0.0.1"
    """Interface ``steakhouse serve`` listens on (``0.0.0.0`` in the container)."""
    port: int = Field(default=8000, ge=0, le=65535)
    """TCP port of ``steakhouse serve``."""
    database_url: str = Field(
        default=DEFAULT_DATABASE_URL,
        validation_alias=AliasChoices("STEAKHOUSE_DATABASE_URL", "DATABASE_URL", "database_url"),
    )
    """SQLAlchemy URL of the store: a SQLite file by default, PostgreSQL for real deployments."""
    study_files: tuple[Path, ...] = DEFAULT_STUDIES
    """Study YAML files served; each is validated at start and an invalid one stops the server."""
    admin_token: SecretStr | None = None
    """Bearer token of the admin API; when unset a random one is generated at start and logged."""
    robot_workers: int | None = Field(default=None, ge=0, le=256)
    """Robot planner worker processes (default: ``WORKERS_PER_CORE`` per CPU); 0 runs planners in the server
    process."""
    robot_factory: str = "planner.robot_catalog:build"
    """``module:function`` building a robot policy from ``(name, layout, rules, setup)``: the catalogue of installed
    robots, shipped and plug-ins (docs/robots.md); tests and benchmarks name their own."""
    decision_deadline_fraction: float = Field(default=0.8, gt=0.0, le=1.0)
    """A robot decision must arrive within this fraction of the tick period; later ones are discarded."""
    flush_interval_s: float = Field(default=0.5, gt=0.0, le=1.0)
    """The background writer commits tick and event rows at least this often (a crash loses at most this)."""
    max_message_bytes: int = Field(default=4096, ge=256, le=1 << 20)
    """Client websocket messages above this size are answered with a ``too_large`` error."""
    ws_max_frame_bytes: int = Field(default=1 << 20, ge=1024)
    """Frames above this are refused by the websocket layer itself (connection closed with 1009)."""
    static_dir: Path | None = None
    """Folder of the browser client served at ``/`` (default: ``./static`` or the repository's ``static/``)."""
    sweep_interval_s: float = Field(default=30.0, gt=0.0)
    """How often trials left running by a vanished participant or a crashed server are checked."""
    join_rate_per_minute: int = Field(default=60, ge=0)
    """Joins allowed per client address and minute (bursts up to the same number; 0 = no limit)."""
    max_live_trials: int | None = Field(default=None, ge=1, le=10_000)
    """Live trials this process runs at once; more participants wait for a slot (default: derived from the
    CPU count, ``server.game.admission.default_capacity``; docs/operations.md, "Admission control")."""
    admission_max_wait_s: float = Field(default=DEFAULT_MAX_WAIT_S, gt=0, le=86_400)
    """A participant who waited this long for a slot is screened out (reason ``server_full``)."""
    resume_link_minutes: int = Field(default=60, ge=1, le=7 * 24 * 60)
    """How long a resume link made in the admin (moving a participant to a new device) stays valid."""
    max_body_bytes: int = Field(default=64 * 1024, ge=1024, le=16 << 20)
    """Request bodies above this many bytes are refused with 413 before they are read (``server.security``)."""
    log_level: Literal["debug", "info", "warning", "error"] = "info"

    @field_validator("database_url")
    @classmethod
    def _normalise_url(cls, url: str) -> str:
        url = url.strip()
        for prefix in ("postgres://", "postgresql://"):
            if url.startswith(prefix):
                return "postgresql+psycopg://" + url[len(prefix):]
        if not (url.startswith(("sqlite", "postgresql"))):
            raise ValueError("only sqlite:/// and postgresql:// URLs are supported")
        return url

    @field_validator("study_files")
    @classmethod
    def _need_studies(cls, files: tuple[Path, ...]) -> tuple[Path, ...]:
        if not files:
            raise ValueError("at least one study file is needed")
        return files

    @field_validator("robot_factory")
    @classmethod
    def _factory_path(cls, value: str) -> str:
        module, _, attr = value.partition(":")
        if not module or not attr:
            raise ValueError("use module:function, e.g. planner.robot_catalog:build")
        return value

    @property
    def workers(self) -> int:
        """The number of robot worker processes actually used."""
        return self.robot_workers if self.robot_workers is not None else default_workers()

    @property
    def live_trial_capacity(self) -> int:
        """The number of live trials this process admits at once."""
        return self.max_live_trials if self.max_live_trials is not None else default_capacity()

    def static_root(self) -> Path | None:
        """The client folder to serve, or ``None`` when there is no client with files."""
        candidates = [self.static_dir] if self.static_dir is not None else [Path("static"), _REPO_STATIC]
        for folder in candidates:
            if folder is not None and folder.is_dir() and any(folder.iterdir()):
                return folder.resolve()
        return None
