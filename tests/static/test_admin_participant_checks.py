"""The admin dashboard for an online study: a study without a completion code is flagged at the top of its
card, the Trials list names participants by their recruiting id (the public id in the tooltip), and the
participants table shows the device check."""

from __future__ import annotations

import pytest
from steakhouse_admin import PRACTICE_STUDY, REPLAY_STUDY, admin_page, admin_server, in_thread, login  # noqa: F401
from steakhouse_testing import Player

pytestmark = pytest.mark.browser

PHONE = {"screen_width": 390, "screen_height": 844, "viewport_width": 390, "viewport_height": 844,
         "pixel_ratio": 3, "fine_pointer": False, "touch": True}


def test_a_study_without_a_completion_code_is_flagged(admin_server, admin_page):  # noqa: F811
    page = admin_page()
    login(page, admin_server)
    page.wait_for_selector(f"#study-{PRACTICE_STUDY}")
    banner = page.locator(f"#warnings-{PRACTICE_STUDY}")
    assert banner.is_visible()
    assert banner.locator("h3").inner_text() == "No usable completion code"
    assert "recruiting.completion_code" in banner.inner_text()
    assert page.locator(f"#warnings-{REPLAY_STUDY}").count() == 0, "a study with a code is not flagged"
    assert [w["code"] for w in next(s for s in admin_server.get("/api/admin/studies")
                                    if s["id"] == PRACTICE_STUDY)["warnings"]] == ["no_completion_code"]


def test_trials_show_the_recruiting_id_and_participants_their_device(admin_server, admin_page):  # noqa: F811
    public_id, trial_id = admin_server.finished_trial("pid-trials-list")

    async def report_a_phone() -> str:
        player = Player(admin_server.url)
        joined = await player.join(REPLAY_STUDY, PROLIFIC_PID="pid-phone")
        (await player.post("/api/session/device", PHONE)).raise_for_status()
        await player.close()
        return str(joined["participant_id"])

    phone_id = in_thread(report_a_phone)
    page = admin_page()
    login(page, admin_server, hash_="#/trials")
    row = page.locator(f"#trials-table tr[data-trial='{trial_id}']")
    row.wait_for()
    who = row.locator(".who")
    assert who.inner_text() == "pid-trials-list" and who.get_attribute("title") == f"public id {public_id}"
    page.goto(f"{admin_server.url}/admin/#/participants?study={REPLAY_STUDY}")
    phone_row = page.locator(f"#participants-table tr[data-participant='{phone_id}']")
    phone_row.wait_for()
    assert "small screen, touch only (390×844)" in phone_row.inner_text()
