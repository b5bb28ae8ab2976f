"""A recruiting id is not a password, in real Chromium: the same link opened in another browser shows a clear
page and gets nothing of the session; the researcher's one-time resume link moves the participant there
(static/js/landing.js, docs/protocol.md §1)."""

from __future__ import annotations


def _expect_logged(problems: list[str], status: int) -> None:
    """The browser logs a refused request itself; that one line is expected, nothing else."""
    expected = [p for p in problems if f"status of {status}" in p]
    assert len(expected) == 1, problems
    problems.remove(expected[0])


def test_another_browser_with_the_same_id_is_refused_and_a_resume_link_moves_the_session(study_server, new_page):
    first, _ = new_page()
    link = study_server.link(PROLIFIC_PID="takeover-1")
    first.goto(link)
    first.click("#consent-agree")
    first.wait_for_selector("#instructions-done")
    token = first.evaluate("() => JSON.parse(localStorage.getItem('steakhouse.session.browser_flow')).token")

    second, problems = new_page()
    second.goto(link)
    second.wait_for_selector("#message-title")
    assert second.inner_text("#message-title") == "This ID has already started in another browser"
    assert "contact the researcher" in second.inner_text("#message")
    assert second.evaluate("() => localStorage.getItem('steakhouse.session.browser_flow')") is None
    _expect_logged(problems, 409)
    first.reload()
    first.wait_for_selector("#instructions-done")  # the first browser goes on, with the same token
    assert first.evaluate("() => JSON.parse(localStorage.getItem('steakhouse.session.browser_flow')).token") == token

    public_id = first.evaluate("() => JSON.parse(localStorage.getItem('steakhouse.session.browser_flow')).participant")
    made = study_server.admin.post(f"/api/admin/participants/{public_id}/resume_link")
    assert made.status_code == 200, made.text
    second.goto(study_server.url + made.json()["path"])
    second.wait_for_selector("#instructions-done")  # where the participant was: consent already given
    assert "#resume" not in second.url, "the used link leaves the address bar"
    second.reload()
    second.wait_for_selector("#instructions-done")

    third, problems = new_page()
    third.goto(study_server.url + made.json()["path"])
    third.wait_for_selector("#message-title")
    assert third.inner_text("#message-title") == "This link is no longer valid"
    _expect_logged(problems, 410)
