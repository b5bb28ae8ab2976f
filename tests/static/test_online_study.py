"""A whole online study in real Chromium, played only from what the page shows: the device check, consent
with durations from the study, instructions with the recipe, the comprehension quiz (a wrong answer, its
explanation, a retry), a practice and a main round in which every task is chosen from the enabled buttons
and the recipe strip (never the server's hint), a blocked task explained, the questionnaire with a choice and
a free-text answer, and the completion code; then what the store holds. Screenshots of every page."""

from __future__ import annotations

import time

import pytest
from sqlalchemy import select
from steakhouse_browser import check_mask, kitchen, screenshot, wait_drawn

from store.tables import AnswerRow, EventRow, ParticipantRow, QuizAttemptRow

pytestmark = pytest.mark.browser

STUDY = "online_study"
TIMEOUT = 20_000
# The recipe's empty-handed steps and the task that does each (what a participant reads off the recipe strip
# and the task buttons): the order comes from the strip on the page.
EMPTY_HANDED = {"steak.meat": "pickup_meat", "garnish.onion": "pickup_onion", "garnish.chop": "chop_onion",
                "plate.plate": "pickup_plate", "plate.wash": "wash_plate", "plate.take_out": "pickup_clean_plate"}
# What the recipe strip highlights for the one task the hands allow (besides putting it on a counter).
HELD_STEP = {"drop_meat": "steak.grill", "drop_onion": "garnish.board", "drop_plate": "plate.sink",
             "pickup_steak": "serve.steak", "pickup_garnish": "serve.garnish", "deliver_dish": "serve.serve"}
COMMENT = '=HYPERLINK("http://x.example","click"), then "quotes",\nand a second line'


def enabled_tasks(page) -> list[str]:
    tasks: list[str] = page.eval_on_selector_all("button[data-subtask]", "bs => bs.filter(b => b.getAttribute('aria-disabled')"
                                      " === 'false').map(b => b.dataset.subtask)")
    return tasks


def wait_idle(page) -> bool:
    """Wait until the cook has no task; False when the round is over (every order delivered: the summary is
    on its way)."""
    over = ("() => document.querySelector('#round-summary') ||"
            " document.querySelector('#hud-orders').textContent === '0'")
    page.wait_for_function(f"() => ({over})() || (document.querySelector('#hud-task').parentElement.dataset.subtask"
                           " === '' && !document.querySelector('button.task-button.pending'))", timeout=TIMEOUT)
    return not page.evaluate(over)


def play_from_the_page(page, shots: dict[str, str] | None = None) -> list[str]:
    """Play a round choosing each task from what the page shows: with something in hand, the one enabled task
    that is not "put on counter" (checked against the recipe strip's highlight); with empty hands, the next
    empty-handed step of the recipe strip. Returns the tasks chosen."""
    order = [EMPTY_HANDED[s] for s in page.eval_on_selector_all(".recipe-item", "ss => ss.map(s => s.dataset.step)")
             if s in EMPTY_HANDED]
    assert order == ["pickup_meat", "pickup_onion", "chop_onion", "pickup_plate", "wash_plate", "pickup_clean_plate"]
    chosen: list[str] = []
    shots = dict(shots or {})
    while wait_idle(page):
        enabled = enabled_tasks(page)
        if "pickup_meat" in enabled:  # empty hands: every pickup is possible
            assert "deliver_dish" not in enabled and "drop_on_counter" not in enabled
            assert order, f"nothing left to do after {chosen}; the page says: {page.inner_text('#task-note')!r}"
            task = order.pop(0)
        else:
            fitting = [t for t in enabled if t != "drop_on_counter"]
            assert len(fitting) == 1, (enabled, chosen)
            (task,) = fitting
            assert page.get_attribute("#recipe", "data-current") == HELD_STEP[task]
        page.click(f"button[data-subtask='{task}']")
        chosen.append(task)
        if task in shots:
            page.wait_for_function(f"() => document.querySelector('#hud-task').parentElement.dataset.subtask === '{task}'"
                                   " || document.querySelector('#round-summary')", timeout=TIMEOUT)
            if page.query_selector("#round-summary") is None:
                screenshot(page, shots.pop(task))
    return chosen


def public_id_of(server, recruit_id: str) -> str:
    public_id: str = next(p["participant_id"] for p in server.get("/api/admin/participants")
                          if p["recruiting"].get("PROLIFIC_PID") == recruit_id)
    return public_id


def stored(server, public_id: str, model):
    with server.services.store.transaction() as session:
        participant = session.scalar(select(ParticipantRow).where(ParticipantRow.public_id == public_id))
        rows = session.scalars(select(model).where(model.participant_id == participant.id)).all()
        return participant, rows


def test_a_participant_takes_the_whole_online_study_from_what_the_page_shows(study_server, new_page):
    page, _ = new_page()
    page.goto(study_server.link(STUDY, PROLIFIC_PID="online-1", STUDY_ID="st", SESSION_ID="se"))
    page.wait_for_selector("#consent-agree")
    consent = page.inner_text("#consent")
    assert "{" not in consent and "minutes" in consent and "step" not in consent.lower()
    screenshot(page, "consent")
    page.click("#consent-agree")

    page.wait_for_selector("#instructions .picture-pair canvas")
    assert page.locator("#instructions-recipe .recipe-step").count() == 13
    instructions = page.inner_text("#instructions")
    assert "tick" not in instructions.lower() and " step" not in instructions.lower().replace("the step you are", "")
    screenshot(page, "instructions", full_page=True)
    page.click("#instructions-done")

    page.wait_for_selector("#quiz-submit")
    screenshot(page, "quiz")
    page.click("label[for='quiz-black_cells-0']")  # wrong on purpose
    page.click("label[for='quiz-cancel_task-0']")
    page.click("#quiz-submit")
    page.wait_for_function("() => document.querySelector('#quiz-black_cells-explanation').textContent !== ''")
    assert "outside your field of view" in page.inner_text("#quiz-black_cells-explanation")
    assert page.inner_text("#quiz-cancel_task-explanation") == ""
    assert "2 of 3" in page.inner_text("#quiz-attempts")
    screenshot(page, "quiz_wrong_answer")
    page.click("label[for='quiz-black_cells-1']")
    page.click("#quiz-submit")

    page.wait_for_selector("#round-intro[data-status='new']")
    screenshot(page, "practice_intro")
    page.click("#start-round")
    practice = wait_drawn(page)
    assert page.is_hidden("#hud-score"), "a practice round that is not scored shows no score"
    # A task the hands do not allow is disabled with its reason and never sent.
    deliver = page.locator("button[data-subtask='deliver_dish']")
    assert deliver.get_attribute("aria-disabled") == "true"
    assert deliver.get_attribute("title") == "You need a finished dish in your hands"
    deliver.focus()
    assert page.inner_text("#task-why") == "Deliver dish: You need a finished dish in your hands."
    deliver.click(force=True)  # a person can still click it: only the reason shows
    assert page.inner_text("#task-note") == "Deliver dish: You need a finished dish in your hands."
    # A task that cannot progress says why, then ends itself.
    page.click("button[data-subtask='chop_onion']")
    page.wait_for_function("() => document.querySelector('#task-note').textContent.includes('stopped')",
                           timeout=TIMEOUT)
    assert page.inner_text("#task-note") == "Chop onion stopped: There is no onion on the board."
    screenshot(page, "trial_task_blocked")
    chosen = play_from_the_page(page)
    page.wait_for_selector("#round-summary")
    assert page.query_selector("#summary-score") is None and page.inner_text("#summary-delivered") == "1"
    assert "seconds" in page.inner_text("#summary-text") and "step" not in page.inner_text("#round-summary").lower()
    screenshot(page, "practice_summary")
    page.click("#continue")

    page.wait_for_selector("#start-round")
    screenshot(page, "round_intro")
    page.click("#start-round")
    main = wait_drawn(page)
    assert main.trial != practice.trial and page.is_visible("#hud-score")
    chosen_main = play_from_the_page(page, shots={"drop_meat": "trial", "pickup_garnish": "trial_recipe_garnish"})
    page.wait_for_selector("#summary-score")
    assert page.inner_text("#summary-score") == "20"
    screenshot(page, "round_summary")
    page.click("#continue")

    page.wait_for_selector("#questionnaire-submit")
    page.click("#questionnaire-submit")
    assert page.locator("fieldset.invalid").count() == 3, "the rating, the reversed rating and the choice"
    screenshot(page, "questionnaire_required", full_page=True)
    page.click("label[for='item-fluency-6']")
    page.click("label[for='item-effort-2']")
    page.click("label[for='item-hand-1']")
    page.fill("#item-comment-text", COMMENT)
    assert "character" in page.inner_text("#item-comment-count")
    screenshot(page, "questionnaire", full_page=True)
    page.click("#questionnaire-submit")

    page.wait_for_selector("#completion-code")
    assert page.inner_text("#completion-code") == "ONLINE-OK-7"
    screenshot(page, "end")

    public_id = public_id_of(study_server, "online-1")
    participant, attempts = stored(study_server, public_id, QuizAttemptRow)
    assert participant.status == "completed"
    assert participant.device is not None and participant.device["problems"] == []
    assert participant.device["fine_pointer"] is True and participant.device["viewport_width"] == 1280
    assert [(a.attempt, a.passed, a.wrong) for a in attempts] == [(1, False, ["black_cells"]), (2, True, [])]
    _, answers = stored(study_server, public_id, AnswerRow)
    assert {a.item_id: (a.value, a.text) for a in answers} == {
        "fluency": (6, None), "effort": (2, None), "hand": (1, "Right"), "comment": (None, COMMENT)}
    events = study_server.events(practice.trial, until=lambda kinds: "subtask_blocked" in kinds)
    blocked = [e["payload"] for e in events if e["kind"] == "subtask_blocked"]
    assert blocked == [{"subtask": "chop_onion", "reason": "nothing_to_chop", "item": None}]
    selected = [e["payload"]["subtask"] for e in events if e["kind"] == "select_subtask"]
    assert "deliver_dish" not in selected[:2], "the disabled task was never sent"
    assert selected == ["chop_onion", *chosen]
    assert [e["payload"]["subtask"] for e in study_server.events(main.trial)
            if e["kind"] == "select_subtask"] == chosen_main


def reach_first_round(page, link: str) -> None:
    """Landing to the practice round's intro: consent, instructions, the quiz answered right at once."""
    page.goto(link)
    page.click("#consent-agree")
    page.click("#instructions-done")
    page.click("label[for='quiz-black_cells-1']")
    page.click("label[for='quiz-cancel_task-0']")
    page.click("#quiz-submit")
    page.wait_for_selector("#start-round")


@pytest.mark.parametrize("viewport", [(1280, 720), (1920, 1080)])
def test_the_kitchen_fills_the_view_and_black_stays_black(study_server, new_page, viewport):
    page, _ = new_page(viewport=viewport)
    reach_first_round(page, study_server.link(STUDY, PROLIFIC_PID=f"fill-{viewport[0]}"))
    page.click("#start-round")
    drawn = wait_drawn(page)
    layout = kitchen("practice")
    assert drawn.bounds == (0, 0, 10, 7), "floor, stations and one ring: not the 15 × 10 grid"
    stage = page.eval_on_selector("#stage", "el => [el.clientWidth, el.clientHeight]")
    canvas = page.eval_on_selector("#kitchen", "el => [el.getBoundingClientRect().width, el.getBoundingClientRect().height]")
    cell = drawn.cell_css
    assert stage[0] - canvas[0] < cell or stage[1] - canvas[1] < cell, (stage, canvas, cell)
    assert canvas[0] * canvas[1] > 0.55 * stage[0] * stage[1], "the kitchen fills most of the stage"
    black, shown = check_mask(page, layout)
    assert black and shown
    screenshot(page, f"trial_{viewport[0]}x{viewport[1]}")


def test_a_small_screen_or_a_phone_is_asked_for_a_computer_and_that_is_recorded(study_server, new_page):
    small, _ = new_page(viewport=(900, 560))
    small.goto(study_server.link(STUDY, PROLIFIC_PID="device-small"))
    small.wait_for_selector("#device[data-problems='small_screen']")
    assert "1024 × 600" in small.inner_text("#device")
    screenshot(small, "device_small_screen")
    phone, _ = new_page(viewport=(390, 844), scale=3, is_mobile=True, has_touch=True)
    phone.goto(study_server.link(STUDY, PROLIFIC_PID="device-phone"))
    phone.wait_for_selector("#device")
    assert phone.get_attribute("#device", "data-problems") == "small_screen touch_only"
    assert phone.inner_text("#device-title") == "Please use a computer with a keyboard"
    screenshot(phone, "device_phone")
    people = {p["recruiting"].get("PROLIFIC_PID"): p for p in study_server.get("/api/admin/participants")}
    assert people["device-small"]["device"]["problems"] == ["small_screen"]
    assert people["device-phone"]["device"] == {**people["device-phone"]["device"], "touch": True,
                                                "fine_pointer": False, "problems": ["small_screen", "touch_only"]}
    assert people["device-phone"]["state"] == "consent", "the same link continues on a computer"


def test_failing_the_quiz_too_often_ends_with_the_screen_out_code(study_server, new_page):
    page, _ = new_page()
    page.goto(study_server.link(STUDY, PROLIFIC_PID="quiz-fail"))
    page.click("#consent-agree")
    page.click("#instructions-done")
    for attempt in range(3):
        page.click("label[for='quiz-black_cells-0']")
        page.click("label[for='quiz-cancel_task-1']")
        page.click("#quiz-submit")
        if attempt < 2:
            page.wait_for_function(f"() => document.querySelector('#quiz-attempts').textContent.includes('{2 - attempt} of 3')")
    page.wait_for_selector("#finish[data-kind='screen_out']")
    assert page.inner_text("#completion-code") == "ONLINE-OUT-3"
    assert "questions about the instructions" in page.inner_text("#finish-text")
    screenshot(page, "screened_out_quiz")


def test_a_second_tab_says_the_round_is_in_progress_and_leaving_asks_first(study_server, new_page):
    page, _ = new_page()
    link = study_server.link(STUDY, PROLIFIC_PID="tabs-1")
    reach_first_round(page, link)
    page.click("#start-round")
    wait_drawn(page)
    context = page.context
    other = context.new_page()
    other.goto(link)
    other.wait_for_selector("#round-intro[data-status='in_progress']")
    assert "already in progress" in other.inner_text("#round-text")
    assert other.inner_text("#start-round") == "Continue the round"
    screenshot(other, "round_in_progress")
    other.close()

    public_id = public_id_of(study_server, "tabs-1")
    first_step = study_server.participant(public_id)["step"]
    dialogs: list[str] = []

    def stay(dialog) -> None:
        dialogs.append(dialog.type)
        dialog.dismiss()

    page.on("dialog", stay)
    page.close(run_before_unload=True)
    for _ in range(100):  # the question is asked asynchronously: wait for it, not for a time
        if dialogs:
            break
        page.wait_for_timeout(50)
    assert dialogs == ["beforeunload"], "leaving during a round asks for confirmation first"
    assert not page.is_closed(), "dismissing the question keeps the round open"
    page.remove_listener("dialog", stay)
    page.close()  # the participant leaves after all
    for _ in range(400):  # the 1 s grace passes and the server ends the round: wait for that state
        if study_server.participant(public_id)["step"] > first_step:
            break
        time.sleep(0.05)

    back = context.new_page()
    back.goto(link)
    back.wait_for_selector("#page-notice")
    assert "ended while you were away" in back.inner_text("#page-notice")
    assert back.inner_text("#round-title") == "Round 1 of 1"
    screenshot(back, "round_ended_while_away")
    rows = study_server.trials(public_id)
    assert [(r["kind"], r["status"], r["end_reason"]) for r in rows] == [("practice", "abandoned", "grace_expired")]


def test_a_link_without_the_participant_id_is_refused_but_a_test_run_is_not(study_server, new_page):
    page, problems = new_page()
    page.goto(study_server.link(STUDY))
    page.wait_for_selector("#message-title")
    assert page.inner_text("#message-title") == "This link is incomplete"
    assert "recruiting site" in page.inner_text("#message")
    expected = [p for p in problems if "status of 422" in p]
    assert len(expected) == 1, problems  # the browser logs the refused join itself
    problems.remove(expected[0])
    tester, _ = new_page()
    tester.goto(study_server.link(STUDY, test_run="1"))  # a participant cannot make themselves a test run
    tester.wait_for_selector("#message-title")
    assert tester.inner_text("#message-title") == "Test runs start from the admin dashboard"
    test_link = study_server.get(f"/api/admin/studies/{STUDY}/links")["test_run"]["path"]
    tester.goto(study_server.url + test_link)
    tester.wait_for_selector("#consent-agree")
