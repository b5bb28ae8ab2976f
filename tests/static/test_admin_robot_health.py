"""The dashboard flags invalid trials (robot decisions past their deadline): a badge with the reason on the
trial, a count on the participant, and a warning in the live view of a trial as soon as it is invalid."""

from __future__ import annotations

from dataclasses import replace

import pytest
from steakhouse_admin import REPLAY_STUDY, admin_page, admin_server, login  # noqa: F401

from store import trials

pytestmark = pytest.mark.browser

REASON = "robot decisions missed their deadline: 30 of 60 (50.0 % > 5 %)"


def test_an_invalid_trial_is_flagged_on_the_trial_and_the_participant(admin_server, admin_page):  # noqa: F811
    public_id, trial_id = admin_server.finished_trial("pid-invalid")
    with admin_server.thread.services.store.transaction() as session:
        trials.record_health(session, trial_id, decisions=60, missed=30, invalid_reason=REASON)
    page = admin_page()
    login(page, admin_server, hash_=f"#/trials?participant={public_id}")
    row = f"#trials-table tr[data-trial='{trial_id}']"
    page.wait_for_selector(row)
    assert "invalid" in page.inner_text(row) and REASON in page.inner_text(row)

    page.goto(f"{admin_server.url}/admin/#/participants?study={REPLAY_STUDY}")
    person = f"#participants-table tr[data-participant='{public_id}']"
    page.wait_for_selector(f"{person} .invalid-trials")
    assert page.inner_text(f"{person} .invalid-trials") == "1 invalid trial"


def test_the_live_view_warns_once_the_trial_is_invalid(admin_server, admin_page):  # noqa: F811
    player = admin_server.live_trial("pid-frozen")
    page = admin_page()
    login(page, admin_server, hash_=f"#/live/{player.trial_id}")
    page.wait_for_selector("#missed-share")
    assert page.locator("#live-invalid").count() == 0
    game = admin_server.thread.services.registry.games[player.trial_id]
    # What the game loop does when the share passes the threshold (server.game.health), without overloading
    # the machine: the next live-view poll shows it.
    game.keeper.health = replace(game.health, decisions=40, missed=40, invalid_reason=REASON)
    page.wait_for_selector("#live-invalid")
    assert REASON in page.inner_text("#live-invalid")
    assert page.inner_text("#missed-share").endswith("% (limit 5 %)")
    player.stop()
