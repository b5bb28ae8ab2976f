"""The admin dashboard in real Chromium: without the admin token nothing but the login form is shown (and the
API answers 401); with it, studies with their condition orders (target vs achieved), recruiting links and
downloads, participants with their progress, answers and flags set through the admin API."""

from __future__ import annotations

import pytest
from steakhouse_admin import (ADMIN_TOKEN, REPLAY_STUDY, admin_page, admin_server, login,  # noqa: F401
                              screenshot)

pytestmark = pytest.mark.browser


def test_without_the_token_nothing_is_shown(admin_server, admin_page):  # noqa: F811
    page = admin_page()
    page.goto(f"{admin_server.url}/admin/#/live")
    page.wait_for_selector("#login-form")
    assert page.is_hidden("#admin-nav") and page.is_hidden("#logout")
    assert REPLAY_STUDY not in page.inner_text("body")
    screenshot(page, "admin_login")

    page.fill("#admin-token", "not-the-token")
    page.click("#login-submit")
    page.wait_for_function("() => document.querySelector('#login-error').textContent.includes('not valid')")
    assert page.is_hidden("#admin-nav") and page.query_selector("#studies") is None
    assert page.evaluate("() => sessionStorage.getItem('steakhouse.admin.token')") is None

    page.evaluate("() => sessionStorage.setItem('steakhouse.admin.token', 'stale-token')")
    page.reload()
    page.wait_for_function("() => document.querySelector('#login-error') &&"
                           " document.querySelector('#login-error').textContent.includes('not valid')")
    assert page.is_hidden("#admin-nav") and REPLAY_STUDY not in page.inner_text("body")

    for path in ("/api/admin/studies", "/api/admin/live", f"/api/admin/studies/{REPLAY_STUDY}/links",
                 "/api/admin/participants", "/api/admin/trials/1/frames"):
        assert page.request.get(admin_server.url + path).status == 401
        assert page.request.get(admin_server.url + path, headers={"Authorization": "Bearer stale-token"}).status == 401

    login(page, admin_server)
    assert page.evaluate("() => sessionStorage.getItem('steakhouse.admin.token')") == ADMIN_TOKEN
    page.click("#logout")
    page.wait_for_selector("#login-form")
    assert page.evaluate("() => sessionStorage.getItem('steakhouse.admin.token')") is None
    assert page.is_hidden("#admin-nav")


def test_studies_show_orders_links_and_downloads(admin_server, admin_page):  # noqa: F811
    admin_server.finished_trial("pid-studies")
    page = admin_page()
    login(page, admin_server)
    card = f"#study-{REPLAY_STUDY}"
    page.wait_for_selector(f"#orders-{REPLAY_STUDY}")
    [study] = [s for s in admin_server.get("/api/admin/studies") if s["id"] == REPLAY_STUDY]
    shown = page.eval_on_selector_all(f"#orders-{REPLAY_STUDY} tbody tr",
                                      "rows => rows.map(r => [Number(r.dataset.counted), Number(r.dataset.target)])")
    counted = [o["counted"] for o in study["orders"]]
    assert [c for c, _ in shown] == counted and sum(counted) >= 1
    assert [t for _, t in shown] == [-(-sum(counted) // len(counted))] * len(counted)

    page.fill(f"#planned-{REPLAY_STUDY}", "10")
    page.dispatch_event(f"#planned-{REPLAY_STUDY}", "change")
    page.wait_for_function(f"() => document.querySelector('#orders-{REPLAY_STUDY} tbody tr').dataset.target === '5'")

    link = page.input_value(f"#link-participant-{REPLAY_STUDY}")
    assert link == (f"{admin_server.url}/?study={REPLAY_STUDY}&PROLIFIC_PID={{{{%PROLIFIC_PID%}}}}"
                    "&STUDY_ID={{%STUDY_ID%}}&SESSION_ID={{%SESSION_ID%}}")
    assert page.input_value(f"#link-test-{REPLAY_STUDY}").startswith(f"{admin_server.url}/?study={REPLAY_STUDY}#test=")
    assert "valid until" in page.inner_text(card)
    assert "https://recruit.example/complete?cc=DASH-OK-9" in page.inner_text(card)

    export = admin_server.admin.get(f"/api/admin/studies/{REPLAY_STUDY}/export.zip")
    if export.status_code == 404:
        page.click(f"#export-{REPLAY_STUDY}")
        page.wait_for_function(f"() => document.querySelector('#download-status-{REPLAY_STUDY}')"
                               ".textContent.includes('not available')")
    else:
        with page.expect_download() as download:
            page.click(f"#export-{REPLAY_STUDY}")
        assert download.value.suggested_filename == f"{REPLAY_STUDY}-export.zip"
    page.evaluate("() => window.localStorage.clear()")
    screenshot(page, "admin_dashboard", full_page=True)


def test_participants_progress_answers_and_flags(admin_server, admin_page):  # noqa: F811
    public_id, _ = admin_server.finished_trial("pid-flags")
    page = admin_page()
    login(page, admin_server, hash_=f"#/participants?study={REPLAY_STUDY}")
    row = f"#participants-table tr[data-participant='{public_id}']"
    page.wait_for_selector(row)
    assert "step" in page.inner_text(row) and "pid-flags" in page.inner_text(row)

    page.click(f"{row} button[data-action='answers']")
    page.wait_for_selector(f"#answers-{public_id}")
    assert "A\t5" in page.inner_text(f"#answers-{public_id}")

    page.click(f"{row} button[data-action='test-run']")
    page.wait_for_selector(f"{row}[data-test-run='true']")
    assert admin_server.get("/api/admin/participants", study_id=REPLAY_STUDY)

    page.click(f"{row} button[data-action='exclude']")
    page.click(f"{row} .exclude-form button[type='submit']")
    assert "reason" in page.inner_text(f"{row} .error")
    page.fill(f"#reason-{public_id}", "pressed keys at random")
    page.click(f"{row} .exclude-form button[type='submit']")
    page.wait_for_selector(f"{row}[data-excluded='true']")
    [stored] = [p for p in admin_server.get("/api/admin/participants", study_id=REPLAY_STUDY)
                if p["participant_id"] == public_id]
    flags = (stored["test_run"], stored["excluded"], stored["exclusion_reason"])
    assert flags == (True, True, "pressed keys at random")
    assert "pressed keys at random" in page.inner_text(row)
    screenshot(page, "admin_participants", full_page=True)

    page.click(f"{row} button[data-action='include']")
    page.wait_for_selector(f"{row}[data-excluded='false']")
    page.click(f"{row} button[data-action='test-run']")
    page.wait_for_selector(f"{row}[data-test-run='false']")


def test_the_participants_table_fits_1280_pixels_with_its_actions_in_view(admin_server, admin_page):  # noqa: F811
    public_id, _ = admin_server.finished_trial("a-rather-long-prolific-id-5f0c2a9e")
    page = admin_page(viewport=(1280, 720))
    login(page, admin_server, hash_=f"#/participants?study={REPLAY_STUDY}")
    row = f"#participants-table tr[data-participant='{public_id}']"
    page.wait_for_selector(row)
    screenshot(page, "admin_participants_1280")
    wrap = page.eval_on_selector("#participants-table", "t => [t.parentElement.scrollWidth, t.parentElement.clientWidth]")
    assert wrap[0] <= wrap[1], f"the table scrolls sideways: {wrap[0]} px in {wrap[1]} px"
    rights = page.eval_on_selector_all(f"{row} button, {row} a",
                                       "els => els.map(e => e.getBoundingClientRect().right)")
    assert rights and max(rights) <= 1280, rights
    height = page.eval_on_selector(row, "r => r.getBoundingClientRect().height")
    assert height <= 80, f"a participant's row is {height} px high"
    assert public_id[:8] in page.inner_text(row)
