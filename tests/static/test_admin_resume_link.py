"""The admin dashboard's "Resume link" button: a one-time link that moves a participant to a new device, shown
on their row; the link works once (server/admin/resume.py, docs/admin.md)."""

from __future__ import annotations

import httpx
import pytest
from steakhouse_admin import REPLAY_STUDY, admin_page, admin_server, in_thread, login  # noqa: F401
from steakhouse_testing import Player

pytestmark = pytest.mark.browser


def test_the_resume_link_button_shows_a_link_that_moves_the_session_once(admin_server, admin_page):  # noqa: F811
    async def join() -> str:
        player = Player(admin_server.url)
        joined = await player.join(REPLAY_STUDY, PROLIFIC_PID="pid-moving")
        await player.close()
        return str(joined["participant_id"])

    public_id = in_thread(join)
    page = admin_page()
    login(page, admin_server, hash_=f"#/participants?study={REPLAY_STUDY}")
    row = page.locator(f"#participants-table tr[data-participant='{public_id}']")
    row.wait_for()
    row.locator("button[data-action='resume-link']").click()
    shown = page.locator(f"#resume-link-{public_id}")
    shown.wait_for()
    url = shown.input_value()
    assert url.startswith(f"{admin_server.url}/?study={REPLAY_STUDY}#resume=") and "works once" in row.inner_text()
    code = url.split("#resume=", 1)[1]
    with httpx.Client(base_url=admin_server.url, timeout=10) as client:
        moved = client.post(f"/api/studies/{REPLAY_STUDY}/resume", json={"code": code})
        assert moved.status_code == 200 and moved.json()["participant_id"] == public_id
        assert client.post(f"/api/studies/{REPLAY_STUDY}/resume", json={"code": code}).status_code == 410
