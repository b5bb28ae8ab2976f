"""Settings are read once from the environment (``STEAKHOUSE_*``, ``DATABASE_URL``) and validated."""

from __future__ import annotations

import logging
import os

import pytest
from pydantic import SecretStr, ValidationError

from server.app import _admin_token
from server.settings import DEFAULT_DATABASE_URL, Settings


@pytest.fixture(autouse=True)
def clean_env(monkeypatch):
    for name in list(os.environ):
        if name.startswith("STEAKHOUSE_") or name == "DATABASE_URL":
            monkeypatch.delenv(name)


def test_defaults():
    settings = Settings()
    assert (settings.host, settings.port, settings.database_url) == ("127.0.0.1", 8000, DEFAULT_DATABASE_URL)
    assert [p.name for p in settings.study_files] == ["demo.yaml", "demo_first_person.yaml", "paper_study.yaml"]
    assert settings.workers == 2 * (os.cpu_count() or 1) and settings.decision_deadline_fraction == 0.8


def test_environment_with_prefix_and_database_url(monkeypatch):
    monkeypatch.setenv("STEAKHOUSE_PORT", "9001")
    monkeypatch.setenv("STEAKHOUSE_ROBOT_WORKERS", "0")
    monkeypatch.setenv("STEAKHOUSE_STUDY_FILES", '["a.yaml"]')
    monkeypatch.setenv("DATABASE_URL", "postgres://u:p@db:5432/steak")
    settings = Settings()
    assert settings.port == 9001 and settings.workers == 0 and [str(p) for p in settings.study_files] == ["a.yaml"]
    assert settings.database_url == "postgresql+psycopg://u:p@db:5432/steak"
    monkeypatch.setenv("STEAKHOUSE_DATABASE_URL", "sqlite:///x.sqlite3")
    assert Settings().database_url == "sqlite:///x.sqlite3"


@pytest.mark.parametrize("name,value", [("STEAKHOUSE_PORT", "70000"), ("DATABASE_URL", "mysql://x/y"),
                                        ("STEAKHOUSE_DECISION_DEADLINE_FRACTION", "0"),
                                        ("STEAKHOUSE_FLUSH_INTERVAL_S", "5"), ("STEAKHOUSE_ROBOT_WORKERS", "-1"),
                                        ("STEAKHOUSE_ROBOT_FACTORY", "no_colon")])
def test_invalid_values_stop_start_up(monkeypatch, name, value):
    monkeypatch.setenv(name, value)
    with pytest.raises(ValidationError):
        Settings()


def test_a_missing_admin_token_is_generated_and_logged(caplog):
    with caplog.at_level(logging.WARNING, logger="server"):
        token = _admin_token(Settings())
    assert len(token) >= 24 and token in caplog.text
    assert _admin_token(Settings(admin_token=SecretStr("fixed"))) == "fixed"
    # A token given as text (as the environment gives it) is taken as the secret too.
    assert _admin_token(Settings(admin_token="fixed")) == "fixed"  # type: ignore[arg-type]  # text, as from the env
