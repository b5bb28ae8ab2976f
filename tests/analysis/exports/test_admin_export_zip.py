"""The admin download ``GET /api/admin/studies/{id}/export.zip``: 401 without the admin token, 404 for an
unknown study, and with the token a zip holding the same files as ``steakhouse export``."""

from __future__ import annotations

import asyncio
import io
import time
import zipfile

import httpx
import pandas as pd
import pytest
from sqlalchemy import create_engine, func, select
from steakhouse_store_study import study_robots
from steakhouse_testing import Player, play_to_end

from analysis.exports.dataset import FILES
from analysis.exports.spss import SAV_FILE
from analysis.exports.study_export import DICTIONARY_FILES, export_study
from store.tables import EventRow

ADMIN = {"Authorization": "Bearer admin-secret"}
PATH = "/api/admin/studies/two_by_two/export.zip"


@pytest.fixture
def server(live_server, study_2x2):
    return live_server([study_2x2], robot_factory=study_robots)


def play_practice(server) -> None:
    async def scenario() -> None:
        player = Player(server.url)
        await player.ready("two_by_two", PROLIFIC_PID="zip-1")
        sock = await player.socket()
        await play_to_end(sock)
        await sock.close()
        await player.close()

    asyncio.run(scenario())
    # the server logs the closed connection after the trial ended; wait until that event is stored
    engine = create_engine(server.services.store.url.render_as_string(hide_password=False))
    deadline = time.monotonic() + 10
    with engine.connect() as conn:
        while not conn.scalar(select(func.count()).select_from(EventRow).where(EventRow.kind == "disconnect")):
            assert time.monotonic() < deadline, "the disconnect event was never stored"
            conn.rollback()
            time.sleep(0.05)
    engine.dispose()


@pytest.mark.parametrize("headers", [{}, {"Authorization": "Bearer wrong"}, {"Authorization": "admin-secret"}])
def test_the_export_needs_the_admin_token(server, headers) -> None:
    with httpx.Client(base_url=server.url) as client:
        participant = client.post("/api/studies/two_by_two/join", json={}).json()
        response = client.get(PATH, headers=headers)
        assert response.status_code == 401
        assert response.json() == {"detail": {"code": "unauthorized", "message": "a valid token is required"}}
        as_participant = client.get(PATH, headers={"Authorization": f"Bearer {participant['token']}"})
        assert as_participant.status_code == 401


def test_with_the_token_the_zip_holds_the_export(server, tmp_path) -> None:
    play_practice(server)
    with httpx.Client(base_url=server.url, headers=ADMIN, timeout=60) as client:
        response = client.get(PATH)
        unknown = client.get("/api/admin/studies/nope/export.zip")
    assert response.status_code == 200
    assert response.headers["content-type"] == "application/zip"
    assert 'filename="two_by_two_export.zip"' in response.headers["content-disposition"]
    assert unknown.status_code == 404 and unknown.json()["detail"]["code"] == "unknown_study"
    archive = zipfile.ZipFile(io.BytesIO(response.content))
    names = {f"two_by_two_export/{name}" for name in (*FILES, SAV_FILE, *DICTIONARY_FILES)}
    assert set(archive.namelist()) == names
    url = server.services.store.url.render_as_string(hide_password=False)
    direct = export_study(url, "two_by_two", tmp_path / "direct")
    for name in FILES:
        zipped = pd.read_csv(archive.open(f"two_by_two_export/{name}"))
        pd.testing.assert_frame_equal(zipped, pd.read_csv(direct.out_dir / name), check_dtype=False)
    trials = pd.read_csv(archive.open("two_by_two_export/trials.csv"))
    assert trials[["kind", "status", "in_cells"]].values.tolist() == [["practice", "finished", 0]]
    assert len(pd.read_csv(archive.open("two_by_two_export/ticks.csv"))) == trials.loc[0, "ticks"]
