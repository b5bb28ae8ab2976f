"""What participants are told about time comes from the study (rounds × horizon ÷ tick rate plus the pages),
and settings a real online study would regret are warned about (the file still validates)."""

from __future__ import annotations

from pathlib import Path

from server.cli import main
from study_config.study import load_study
from study_config.study.duration import (
    CONSENT_SECONDS,
    END_SECONDS,
    INSTRUCTIONS_SECONDS,
    ITEM_SECONDS,
    QUIZ_QUESTION_SECONDS,
    ROUND_PAGES_SECONDS,
    duration_words,
    fill_placeholders,
    study_length,
)
from study_config.study.warnings import study_warnings

STUDY_CONFIG = Path(__file__).resolve().parents[3] / "study_config"
BASE = "id: t\ntitle: Texts\nkitchens: [none_3]\nrobots: [stay]\nfactors: [robot]\n"


def write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "study.yaml"
    path.write_text(BASE + text, encoding="utf-8")
    return path


def test_the_paper_studys_length_is_its_rounds_at_full_length_plus_its_pages():
    study = load_study(STUDY_CONFIG / "paper_study.yaml")
    length = study_length(study)
    # The paper's clock waits for the participant: a round lasts at most its wall-clock limit (240 s).
    assert study.timing.mode == "wait_for_participant"
    assert (length.practice_rounds, length.main_rounds, length.round_seconds) == (1, 4, 240)
    per_round_questions = 5 * ITEM_SECONDS["rating"] + ITEM_SECONDS["text"]
    expected = (CONSENT_SECONDS + INSTRUCTIONS_SECONDS + 3 * QUIZ_QUESTION_SECONDS + 5 * (240 + ROUND_PAGES_SECONDS)
                + 4 * per_round_questions + END_SECONDS)
    assert length.total_seconds == expected
    assert length.minutes == -(-expected // 60)
    values = length.placeholders()
    assert values["round_time"] == "4 minutes" and values["rounds"] == "5" and values["questions_per_round"] == "6"
    consent = fill_placeholders(study.consent, values)
    assert f"up to about {length.minutes} minutes" in consent and "at most\n4 minutes" in consent
    assert "{" not in consent


def test_round_time_is_true_in_both_clocks(tmp_path):
    fixed = load_study(write(tmp_path, "world: {horizon: 300}\ntiming: {tick_rate_hz: 5}\n"))
    waiting = load_study(write(tmp_path, "world: {horizon: 300}\ntiming: {mode: wait_for_participant}\n"))
    chosen = load_study(write(tmp_path, "timing: {mode: wait_for_participant, max_round_seconds: 100}\n"))
    assert study_length(fixed).placeholders()["round_time"] == "60 seconds"
    assert fixed.timing.round_limit_seconds(300) is None, "a fixed_rate round ends at its horizon"
    # The default limit: horizon at the tick rate, three times over.
    assert study_length(waiting).placeholders()["round_time"] == "3 minutes"
    assert waiting.timing.round_limit_seconds(300) == 180
    assert study_length(chosen).placeholders()["round_time"] == "100 seconds"


def test_a_longer_horizon_or_a_slower_clock_lengthens_what_the_texts_promise(tmp_path):
    short = study_length(load_study(write(tmp_path, "world: {horizon: 150}\n")))
    long = study_length(load_study(write(tmp_path, "world: {horizon: 1500}\ntiming: {tick_rate_hz: 2.5}\n")))
    assert (short.round_seconds, long.round_seconds) == (30, 600)
    assert long.minutes > short.minutes
    assert long.placeholders()["round_time"] == "10 minutes"
    assert short.placeholders()["practice_note"] == ""
    assert [duration_words(s) for s in (1, 59.5, 150)] == ["1 second", "60 seconds", "2.5 minutes"]


def test_default_texts_never_say_steps_or_ticks_and_fill_every_placeholder(tmp_path):
    study = load_study(write(tmp_path, "practice: [{kitchen: practice, robot: stay, count: 2}]\n"))
    values = study_length(study).placeholders()
    for text in (study.consent, study.instructions):
        filled = fill_placeholders(text, values)
        assert "{" not in filled and " tick" not in filled.lower() and " step" not in filled.lower()
    assert "The first 2 rounds are practice" in fill_placeholders(study.instructions, values)
    assert fill_placeholders("{minutes} {unknown} {}", values) == f"{values['minutes']} {{unknown}} {{}}"


def warnings_of(tmp_path: Path, text: str) -> list[tuple[str, str]]:
    """The warnings of the study with ``text``, its clock chosen (that warning has its own test)."""
    study = load_study(write(tmp_path, "timing: {mode: fixed_rate}\n" + text))
    return [(w.path, w.code) for w in study_warnings(study)]


def test_a_study_that_does_not_choose_its_clock_is_told_what_the_default_does(tmp_path):
    (unchosen,) = study_warnings(load_study(write(tmp_path, "recruiting: {completion_code: C}\n")))
    assert (unchosen.path, unchosen.code) == ("timing.mode", "clock_not_chosen")
    assert "fixed_rate" in unchosen.reason and "wait_for_participant" in unchosen.reason
    for clock in ("fixed_rate", "wait_for_participant"):
        chosen = load_study(write(tmp_path, f"recruiting: {{completion_code: C}}\ntiming: {{mode: {clock}}}\n"))
        assert study_warnings(chosen) == []
    assert "clock_not_chosen" not in {w.code for w in study_warnings(load_study(STUDY_CONFIG / "paper_study.yaml"))}


def test_recruiting_without_a_completion_code_is_warned_about(tmp_path):
    assert warnings_of(tmp_path, "") == [("recruiting.completion_code", "no_completion_code")]
    assert warnings_of(tmp_path, "recruiting: {completion_redirect_url: 'https://x.example/done'}\n") == []
    assert warnings_of(tmp_path, "recruiting: {url_parameters: []}\n") == []
    assert warnings_of(tmp_path, "recruiting: {completion_code: REPLACE-WITH-YOUR-COMPLETION-CODE}\n") == [
        ("recruiting.completion_code", "placeholder_code")]


def test_full_counterbalancing_beyond_24_orders_says_how_many_participants_a_complete_design_needs(tmp_path):
    five = "kitchens: [none_3, mid_2, none_1, mid_1, side_1]\nfactors: [kitchen]\ncounterbalancing: full\n"
    text = BASE.replace("kitchens: [none_3]\n", "").replace("factors: [robot]\n", "") + five
    path = tmp_path / "five.yaml"
    text += "timing: {mode: fixed_rate}\n"
    path.write_text(text + "recruiting: {completion_code: X}\n", encoding="utf-8")
    (warning,) = study_warnings(load_study(path))
    assert warning.path == "counterbalancing" and warning.code == "many_orders"
    assert "5 conditions gives 120 orders" in warning.reason and "multiple of 120 participants" in warning.reason
    assert "latin_square needs 10" in warning.reason
    four = text.replace(", side_1]", "]")
    path.write_text(four + "recruiting: {completion_code: X}\n", encoding="utf-8")
    assert study_warnings(load_study(path)) == []  # 4! = 24 orders: fine


def test_a_quiz_without_a_screen_out_code_and_misspelt_placeholders_are_warned_about(tmp_path):
    quiz = ("quiz: {questions: [{id: q, text: Q, options: [a, b], answer: 1, explanation: E}]}\n"
            "recruiting: {completion_code: C}\nconsent: 'Takes {minuets} minutes, {minutes} really.'\n")
    assert warnings_of(tmp_path, quiz) == [("recruiting.screen_out_code", "no_screen_out_code"),
                                           ("consent", "unknown_placeholder")]


def test_validate_prints_warnings_on_stderr_and_still_passes(tmp_path, capsys):
    path = write(tmp_path, "timing: {mode: wait_for_participant}\n")
    assert main(["study", "validate", str(path)]) == 0
    out, err = capsys.readouterr()
    assert out.startswith(f"{path}: ok: t")
    assert err == (f"{path}: recruiting.completion_code: warning: recruiting ids are captured (PROLIFIC_PID, "
                   "STUDY_ID, SESSION_ID) but no completion code or redirect is set: participants who finish cannot "
                   "prove it to the recruiting platform\n")


def test_texts_shown_to_participants_that_name_a_condition_are_warned_about(tmp_path):
    text = ("robots: [fov_aware, baseline]\nrecruiting: {completion_code: C}\n"
            "instructions: 'Today you meet the fov_aware robot in none_3; stay near the grill.'\n"
            "questionnaires: [{id: q, title: 'About baseline', items: [{id: a, text: 'Was fov_aware@none_3 fun?', "
            "scale: {min: 1, max: 5, labels: {1: 'like the baseline one'}}}]}]\n")
    (tmp_path / "s").mkdir()
    path = tmp_path / "s" / "study.yaml"
    path.write_text(BASE.replace("robots: [stay]\n", "") + text, encoding="utf-8")
    found = {w.path: w.reason for w in study_warnings(load_study(path)) if w.code == "names_condition"}
    assert found == {
        "instructions": "shown to participants but names 'fov_aware', 'none_3': participants must not learn their "
                        "conditions",
        "questionnaires[0].title": "shown to participants but names 'baseline': participants must not learn their "
                                   "conditions",
        "questionnaires[0].items[0].text": "shown to participants but names 'fov_aware@none_3': participants must "
                                           "not learn their conditions",
        "questionnaires[0].items[0].scale.labels[1]": "shown to participants but names 'baseline': participants "
                                                      "must not learn their conditions",
    }


def plan_rounds(study, order) -> tuple[int, int]:
    from server.flow.plan import build_plan

    trials = [s for s in build_plan(study, order) if s.kind == "trial"]
    return sum(s.trial_kind == "practice" for s in trials), sum(s.trial_kind == "main" for s in trials)


def test_every_shipped_study_promises_the_rounds_each_of_its_participants_plays():
    for path in sorted(STUDY_CONFIG.glob("*.yaml")):
        study = load_study(path)
        length = study_length(study)
        for order in study.condition_orders():
            assert plan_rounds(study, order) == (length.practice_rounds, length.main_rounds), path.name


def test_a_between_participants_design_counts_one_groups_rounds_not_every_groups(tmp_path):
    # The study: a field of view between participants; each group plays its own three conditions.
    study = load_study(_between(tmp_path))
    assert len(study.conditions) == 6
    length = study_length(study)
    assert (length.practice_rounds, length.main_rounds) == (1, 3)
    assert {plan_rounds(study, order) for order in study.condition_orders()} == {(1, 3)}
    consent = fill_placeholders(study.consent, length.placeholders())
    assert "You will play 4 short rounds" in consent and "each of the 3 rounds that count" in consent
    round_pages = 4 * (length.round_seconds + ROUND_PAGES_SECONDS)
    assert length.total_seconds == (CONSENT_SECONDS + INSTRUCTIONS_SECONDS + round_pages + END_SECONDS)


def _between(tmp_path: Path) -> Path:
    path = tmp_path / "between.yaml"
    path.write_text("id: b\ntitle: Between\nkitchens: [none_3]\nrobots: [fov_aware, baseline, stay]\n"
                    "factors: [robot]\nfov_angles: [90, 150]\nbetween: [fov_angle]\n"
                    "practice: [{kitchen: practice, robot: stay}]\n"
                    "timing: {mode: wait_for_participant}\n", encoding="utf-8")
    return path


def test_the_texts_say_what_the_clock_does_for_the_participant(tmp_path):
    waiting = study_length(load_study(write(tmp_path, "timing: {mode: wait_for_participant}\n")))
    fixed = study_length(load_study(write(tmp_path, "timing: {mode: fixed_rate}\n")))
    study = load_study(write(tmp_path, "timing: {mode: wait_for_participant}\n"))
    shown = fill_placeholders(study.instructions, waiting.placeholders())
    assert "The kitchen waits for you" in shown and "press **.** (stay)" in shown
    assert "The robot works on its own" not in shown
    assert "goes on while you think" in fill_placeholders(study.instructions, fixed.placeholders())
