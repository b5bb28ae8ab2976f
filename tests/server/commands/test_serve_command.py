"""``steakhouse serve``: options become settings, invalid studies and settings stop it with clear errors."""

from __future__ import annotations

import os
from typing import Any

import pytest
import uvicorn

from server.cli import main


@pytest.fixture(autouse=True)
def clean_env(monkeypatch):
    for name in list(os.environ):
        if name.startswith("STEAKHOUSE_") or name == "DATABASE_URL":
            monkeypatch.delenv(name)


def test_serve_starts_uvicorn_with_the_options(monkeypatch, study_file, tmp_path):
    seen: dict[str, Any] = {}
    monkeypatch.setattr(uvicorn, "run", lambda app, **kwargs: seen.update(app=app, **kwargs))
    study = study_file()
    url = f"sqlite:///{tmp_path / 'db.sqlite3'}"
    assert main(["serve", "--host", "0.0.0.0", "--port", "8123", "--study", str(study), "--database-url", url,
                 "--workers", "0"]) == 0
    assert (seen["host"], seen["port"], seen["ws_max_size"]) == ("0.0.0.0", 8123, 1 << 20)
    assert seen["app"].title == "Steakhouse Study"


def test_serve_refuses_an_invalid_study(study_file, capsys):
    bad = study_file(robots=["teleporter"])
    assert main(["serve", "--study", str(bad)]) == 1
    err = capsys.readouterr().err
    assert "robots[0]: unknown robot 'teleporter'" in err and "did not start" in err


def test_serve_refuses_two_studies_with_one_id(study_file, tmp_path, capsys):
    first = study_file()
    second = tmp_path / "copy.yaml"
    second.write_text(first.read_text())
    assert main(["serve", "--study", str(first), "--study", str(second)]) == 1
    assert "already used" in capsys.readouterr().err


def test_serve_refuses_invalid_settings(capsys):
    assert main(["serve", "--port", "70000"]) == 2
    assert "invalid settings: port" in capsys.readouterr().err


def test_serve_prints_each_studys_links_the_admin_address_and_warns_about_placeholder_codes(
        monkeypatch, study_file, tmp_path, capsys):
    monkeypatch.setattr(uvicorn, "run", lambda app, **kwargs: None)
    shipped = study_file("shipped", recruiting={"completion_code": "REPLACE-WITH-YOUR-COMPLETION-CODE"})
    ready = study_file("ready", recruiting={"completion_code": "C0DE", "url_parameters": ["PROLIFIC_PID"]})
    url = f"sqlite:///{tmp_path / 'db.sqlite3'}"
    assert main(["serve", "--host", "0.0.0.0", "--port", "8123", "--study", str(shipped), "--study", str(ready),
                 "--database-url", url, "--workers", "0"]) == 0
    out, err = capsys.readouterr()
    assert "Admin dashboard: http://127.0.0.1:8123/admin/" in out
    assert "Study ready: participant link http://127.0.0.1:8123/?study=ready&PROLIFIC_PID={{%PROLIFIC_PID%}}" in out
    assert "test run         http://127.0.0.1:8123/?study=shipped#test=" in out
    assert "WARNING: study shipped: recruiting.completion_code is still the shipped placeholder" in err
    assert "study ready" not in err
