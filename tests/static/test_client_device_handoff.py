"""A participant who opens the study link on a phone is asked for a computer and shown a hand-off code; the same
link on a laptop asks for that code and continues there with it (the phone's session held nothing yet, so the
laptop claims it: docs/protocol.md §1), the phone is signed out, and the hand-off is logged (``session_claimed``).
The link the phone shows continues without typing."""

from __future__ import annotations

import pytest
from steakhouse_browser import screenshot

from store.tables import EventRow, ParticipantRow

pytestmark = pytest.mark.browser

STUDY = "online_study"


def test_a_phone_user_continues_on_a_laptop_with_the_same_link(study_server, new_page):
    link = study_server.link(STUDY, PROLIFIC_PID="walks-to-laptop")
    phone, phone_problems = new_page(viewport=(390, 844), scale=3, is_mobile=True, has_touch=True)
    phone.goto(link)
    phone.wait_for_selector("#device")
    assert "same study link on a laptop" in phone.inner_text("#device")
    assert phone.inner_text("#progress").strip() == "", "no 'Part 1 of N' on the device page"
    screenshot(phone, "handoff_phone")
    [before] = [p for p in study_server.get("/api/admin/participants")
                if p["recruiting"].get("PROLIFIC_PID") == "walks-to-laptop"]

    code = phone.inner_text("#handoff-code").strip()
    assert phone.get_attribute("#handoff-link", "href").endswith(f"#handoff={code}")

    laptop, laptop_problems = new_page(viewport=(1280, 720))
    laptop.goto(link)
    laptop.wait_for_selector("#handoff-input")  # the id alone does not continue the phone's session
    laptop.fill("#handoff-input", "WRONG-CODE")
    laptop.click("#handoff-go")
    laptop.wait_for_function("() => document.querySelector('#message').textContent.includes('not the code')")
    laptop.fill("#handoff-input", code.lower())
    laptop.click("#handoff-go")
    laptop.wait_for_selector("#consent-agree")
    for problem in [p for p in laptop_problems if "status of 409" in p]:  # the browser logs the refused joins
        laptop_problems.remove(problem)
    assert laptop.inner_text("#progress").startswith("Part 1 of")
    screenshot(laptop, "handoff_laptop")
    stored = laptop.evaluate(f"() => JSON.parse(localStorage.getItem('steakhouse.session.{STUDY}'))")
    assert stored["participant"] == before["participant_id"], "the same participant, not a new one"
    [after] = [p for p in study_server.get("/api/admin/participants")
               if p["recruiting"].get("PROLIFIC_PID") == "walks-to-laptop"]
    assert after["device"]["problems"] == [] and after["order_index"] == before["order_index"]

    phone.reload()  # the phone's token no longer works, and the laptop's device passed: the phone is refused
    phone.wait_for_selector("#message-title")
    assert phone.inner_text("#message-title") == "This ID has already started in another browser"
    expected = [p for p in phone_problems if "status of 401" in p or "status of 409" in p]
    for problem in expected:  # the browser logs the refused requests itself
        phone_problems.remove(problem)
    with study_server.services.store.transaction() as session:  # stored with the join, not in a batch
        row = session.query(ParticipantRow).filter_by(public_id=before["participant_id"]).one()
        kinds = [e.kind for e in session.query(EventRow).filter_by(participant_id=row.id)]
    assert kinds.count("session_claimed") == 1 and kinds.count("join_refused") == 1
    assert kinds.count("handoff_refused") == 1
