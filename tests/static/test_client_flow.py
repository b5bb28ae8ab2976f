"""A participant's whole way through a study in real Chromium: landing link, consent, instructions,
practice, one round played by clicking task buttons, the questionnaire, the end page and its redirect;
then what the store holds. Also: declining consent ends politely."""

from __future__ import annotations

import time

import pytest
from sqlalchemy import select
from steakhouse_browser import ONE_DISH, play_by_clicking, press_until_focused, wait_drawn

from steakhouse_browser import RECRUIT_SITE, screenshot
from store.tables import AnswerRow, ParticipantRow

pytestmark = pytest.mark.browser

RECRUITING = {"PROLIFIC_PID": "pid-flow-1", "STUDY_ID": "st-9", "SESSION_ID": "se-3"}


def stored_answers(server, public_id: str) -> dict[str, int | None]:
    with server.services.store.transaction() as session:
        pid = session.execute(select(ParticipantRow.id).where(ParticipantRow.public_id == public_id)).scalar_one()
        rows = session.execute(select(AnswerRow).where(AnswerRow.participant_id == pid)).scalars().all()
        return {f"{r.questionnaire_id}.{r.item_id}": r.value for r in rows}


def test_a_participant_completes_the_whole_study(study_server, new_page):
    page, _ = new_page()
    page.goto(study_server.link(**RECRUITING, other="ignored"))
    page.wait_for_selector("#consent-agree")
    assert "Consent to take part" in page.inner_text("#consent h1")
    screenshot(page, "consent")
    page.click("#consent-agree")

    page.wait_for_selector("#instructions .picture-pair canvas")
    assert page.locator(".legend li").count() >= 15
    screenshot(page, "instructions", full_page=True)
    page.click("#instructions-done")

    page.wait_for_selector("#start-round")
    page.click("#start-round")
    practice = wait_drawn(page)
    assert page.inner_text("#hud-round").startswith("Practice")
    assert page.locator("button[data-subtask]").count() == 13
    assert play_by_clicking(page) == list(ONE_DISH)
    assert page.inner_text("#summary-delivered") == "1"
    page.click("#continue")

    page.wait_for_selector("#start-round")
    page.click("#start-round")
    main = wait_drawn(page)
    assert main.trial != practice.trial
    page.keyboard.press("ArrowRight")  # face the robot, so the screenshot shows it
    wait_drawn(page, "d.robot !== ''")
    page.wait_for_function("() => document.querySelector('#latency').dataset.ms !== undefined")
    screenshot(page, "trial")
    clicked = play_by_clicking(page)
    assert page.inner_text("#summary-score") == "20"
    page.click("#continue")

    page.wait_for_selector("#questionnaire-submit")
    page.click("#questionnaire-submit")
    assert page.locator("fieldset.invalid").count() == 2, "both required items are flagged"
    assert page.evaluate("() => document.activeElement.name") == "item-fluency"
    screenshot(page, "questionnaire_required")
    page.click("label[for='item-fluency-6']")
    page.click("label[for='item-awareness-3']")
    assert page.locator("fieldset.invalid").count() == 0
    page.click("#questionnaire-submit")

    page.wait_for_selector("#completion-code")
    assert page.inner_text("#completion-code") == "BROWSER-OK-42"
    screenshot(page, "end")
    page.wait_for_url(f"{RECRUIT_SITE}complete?cc=BROWSER-OK-42", timeout=15_000)

    public_id = next(p["participant_id"] for p in study_server.get("/api/admin/participants")
                     if p["recruiting"].get("PROLIFIC_PID") == RECRUITING["PROLIFIC_PID"])
    participant = study_server.participant(public_id)
    assert participant["status"] == "completed" and participant["recruiting"] == RECRUITING
    trials = sorted(study_server.trials(public_id), key=lambda t: t["trial_id"])
    assert [(t["trial_id"], t["kind"], t["status"], t["delivered"]) for t in trials] == [
        (practice.trial, "practice", "finished", 1), (main.trial, "main", "finished", 1)]
    replay = study_server.get(f"/api/admin/trials/{main.trial}")
    assert [t["tick"] for t in replay["ticks"]] == list(range(1, trials[1]["ticks"] + 1))
    assert [e["payload"]["subtask"] for e in study_server.events(main.trial) if e["kind"] == "select_subtask"] == clicked
    assert stored_answers(study_server, public_id) == {
        "after_round.fluency": 6, "after_round.awareness": 3, "after_round.comment_free": None}


def test_declining_consent_ends_politely_with_the_screen_out_code(study_server, new_page):
    page, _ = new_page()
    page.goto(study_server.link(PROLIFIC_PID="pid-decline"))
    page.wait_for_selector("#consent-decline")
    press_until_focused(page, "#consent-decline")
    page.keyboard.press("Enter")
    assert page.evaluate("() => document.activeElement.id") == "consent-decline-confirm"
    page.keyboard.press("Enter")
    page.wait_for_selector("#finish[data-kind='screen_out']")
    assert page.inner_text("#completion-code") == "NO-CONSENT-7"
    assert page.query_selector("#redirect-note") is None
    screenshot(page, "screened_out")
    public_id = next(p["participant_id"] for p in study_server.get("/api/admin/participants")
                     if p["recruiting"].get("PROLIFIC_PID") == "pid-decline")
    assert study_server.participant(public_id)["status"] == "screened_out"
    page.reload()
    page.wait_for_selector("#finish[data-kind='screen_out']")
    time.sleep(0.2)


def test_incomplete_and_unknown_links_explain_themselves(study_server, new_page):
    page, problems = new_page()
    page.goto(f"{study_server.url}/")
    page.wait_for_selector("#message-title")
    assert page.inner_text("#message-title") == "This link is incomplete"
    page.goto(study_server.link("no_such_study", PROLIFIC_PID="x"))
    page.wait_for_selector("#message-title")
    assert page.inner_text("#message-title") == "This study is not available"
    expected = [p for p in problems if "status of 404" in p]
    assert len(expected) == 1, problems  # the browser logs the refused study look-up itself
    problems.remove(expected[0])


def test_an_end_page_without_a_payment_code_says_to_contact_the_researcher(study_server, new_page):
    """What a real participant of a study still carrying the shipped placeholder code gets from the server
    (``completion.not_set_up``, tests/server/routes/test_participant_api.py): no code, a clear way on."""
    page, _ = new_page()

    def not_set_up(route):
        response = route.fetch()
        view = response.json()
        view["completion"] = {**view["completion"], "code": None, "redirect_url": None, "not_set_up": True}
        route.fulfill(response=response, json=view)

    page.route("**/api/session/consent", not_set_up)
    page.goto(study_server.link(PROLIFIC_PID="pid-unpaid"))
    page.click("#consent-decline")
    page.click("#consent-decline-confirm")
    page.wait_for_selector("#not-set-up")
    text = page.inner_text("#not-set-up")
    assert "not set up for payment yet" in text and "contact the researcher" in text
    public_id = page.evaluate("() => JSON.parse(localStorage.getItem('steakhouse.session.browser_flow')).participant")
    assert public_id in text, "the participant number to quote"
    assert page.query_selector("#completion-code") is None and page.query_selector("#redirect-note") is None
    screenshot(page, "end_not_set_up")
