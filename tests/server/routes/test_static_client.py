"""The browser client folder is served at ``/`` with ``index.html`` for client-side routes, never over the
API; without client files nothing is mounted."""

from __future__ import annotations

import httpx
import pytest

pytestmark = pytest.mark.store_agnostic


def test_client_files_and_fallback(live_server, study_file, tmp_path):
    folder = tmp_path / "client"
    folder.mkdir()
    (folder / "index.html").write_text("<!doctype html><title>client</title>")
    (folder / "app.js").write_text("export const x = 1;")
    server = live_server([study_file()], static_dir=folder)
    with httpx.Client(base_url=server.url) as client:
        assert "client" in client.get("/").text
        assert client.get("/app.js").text == "export const x = 1;"
        assert "client" in client.get("/play/tiny").text
        missing_api = client.get("/api/nothing")
        assert missing_api.status_code == 404 and "client" not in missing_api.text
        assert client.get("/healthz").json()["status"] == "ok"


def test_without_client_files_the_api_still_works(live_server, study_file, tmp_path):
    empty = tmp_path / "empty"
    empty.mkdir()
    server = live_server([study_file()], static_dir=empty)
    with httpx.Client(base_url=server.url) as client:
        assert client.get("/").status_code == 404
        assert client.post("/api/studies/tiny/join", json={}).status_code == 200
