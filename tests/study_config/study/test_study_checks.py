"""The participant checks a study declares: the comprehension quiz, the device requirements, and the
blocked-subtask time."""

from __future__ import annotations

from pathlib import Path

import pytest

from study_config.study import load_study, validate_study_file
from study_config.study.device import DeviceInfo, DeviceRequirements, device_problems

BASE = "id: t\ntitle: Checks\nkitchens: [none_3]\nrobots: [stay]\nfactors: [robot]\n"

QUIZ = """\
quiz:
  max_attempts: 2
  questions:
    - id: black
      text: What is black?
      options: [A wall, Out of view]
      answer: 2
      explanation: Out of view.
    - id: stop
      text: How to stop?
      options: [Esc, Enter, Tab]
      answer: 1
      explanation: Esc stops.
"""


def write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "study.yaml"
    path.write_text(BASE + text, encoding="utf-8")
    return path


def test_the_quiz_knows_its_correct_options_and_which_answers_are_wrong(tmp_path):
    quiz = load_study(write(tmp_path, QUIZ)).quiz
    assert quiz is not None and quiz.max_attempts == 2
    assert [q.correct for q in quiz.questions] == [1, 0]
    assert quiz.wrong({"black": 1, "stop": 0}) == []
    assert [q.id for q in quiz.wrong({"black": 0, "stop": 0})] == ["black"]
    assert [q.id for q in quiz.wrong({})] == ["black", "stop"]


def test_a_quiz_question_must_have_a_correct_option_among_distinct_ones(tmp_path):
    bad = QUIZ.replace("answer: 2", "answer: 3").replace("[Esc, Enter, Tab]", "[Esc, Esc]").replace(
        "max_attempts: 2", "max_attempts: 0")
    found = [(p.path, p.reason) for p in validate_study_file(write(tmp_path, bad))]
    assert found == [
        ("quiz.max_attempts", "should be greater than or equal to 1 (got 0)"),
        ("quiz.questions[0].answer", "there is no option 3: the question has 2 options (count from 1)"),
        ("quiz.questions[1].options[1]", "duplicate option 'Esc' (already at [0])"),
    ]


@pytest.mark.parametrize(("screen", "fine", "touch", "expected"), [
    ((1280, 720), True, False, []),
    ((1024, 600), True, True, []),           # a touch laptop with a trackpad
    ((768, 1366), True, False, []),          # a monitor turned upright: either orientation counts
    ((1000, 700), True, False, ["small_screen"]),
    ((390, 844), False, True, ["small_screen", "touch_only"]),    # a phone
    ((1366, 1024), False, True, ["touch_only"]),                  # a large tablet
])
def test_small_screens_and_touch_only_devices_are_refused(screen, fine, touch, expected):
    info = DeviceInfo(screen_width=screen[0], screen_height=screen[1], viewport_width=screen[0],
                      viewport_height=screen[1], pixel_ratio=1.0, fine_pointer=fine, touch=touch)
    assert device_problems(DeviceRequirements(), info) == expected
    relaxed = DeviceRequirements(min_width=320, min_height=320, allow_touch_only=True)
    assert device_problems(relaxed, info) == []


def test_device_requirements_and_the_blocked_subtask_time_default_and_convert_to_ticks(tmp_path):
    study = load_study(write(tmp_path, "timing: {tick_rate_hz: 10}\n"))
    assert study.device == DeviceRequirements(min_width=1024, min_height=600, allow_touch_only=False)
    assert study.timing.blocked_subtask_seconds == 3.0 and study.timing.blocked_ticks() == 30
    quick = load_study(write(tmp_path, "timing: {tick_rate_hz: 5, blocked_subtask_seconds: 0.1}\n"))
    assert quick.timing.blocked_ticks() == 1
    found = [(p.path, p.reason) for p in validate_study_file(write(tmp_path, "timing: {blocked_subtask_seconds: 0}\n"))]
    assert found == [("timing.blocked_subtask_seconds", "should be greater than 0 (got 0)")]


def test_a_wall_clock_limit_belongs_to_the_waiting_clock_and_the_engagement_rules_are_checked(tmp_path):
    found = [(p.path, p.reason) for p in validate_study_file(write(tmp_path, "timing: {max_round_seconds: 60}\n"))]
    assert found == [("timing.max_round_seconds", "only a wait_for_participant round has a wall-clock limit; a "
                                                  "fixed_rate round ends at the horizon")]
    bad = "validity: {min_participant_actions: -1, max_idle_pct: 101, max_invalid_rounds: -2}\n"
    paths = {p.path for p in validate_study_file(write(tmp_path, bad))}
    assert paths == {"validity.min_participant_actions", "validity.max_idle_pct", "validity.max_invalid_rounds"}
    study = load_study(write(tmp_path, "timing: {mode: wait_for_participant}\n"))
    assert (study.validity.min_participant_actions, study.validity.max_idle_pct,
            study.validity.max_invalid_rounds) == (1, 95.0, 0)
    assert study.timing.idle_nudge_seconds == 10.0
