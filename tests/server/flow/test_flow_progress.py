"""The participant's state machine accepts exactly the legal transitions."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from server.flow.plan import build_plan
from server.flow.progress import IllegalTransition, Move, Phase, Progress
from study_config import STUDY_DIR
from study_config.catalog import load_one


@pytest.fixture(scope="module")
def plan():
    loaded = load_one(STUDY_DIR / "paper_study.yaml")
    return build_plan(loaded.study, loaded.orders[1])


def walk(plan) -> list[Phase]:
    progress = Progress(plan, 0)
    phases = [progress.phase]
    while progress.phase is not Phase.DONE:
        step = progress.current
        if progress.phase is Phase.CONSENT:
            progress = progress.apply(Move.ACCEPT_CONSENT)
        elif progress.phase is Phase.INSTRUCTIONS:
            progress = progress.apply(Move.FINISH_INSTRUCTIONS)
        elif progress.phase is Phase.QUIZ:
            progress = progress.apply(Move.PASS_QUIZ)
        elif progress.phase in (Phase.PRACTICE, Phase.TRIAL):
            assert step.trial_kind is not None and step.index is not None
            progress = progress.apply(Move.END_TRIAL, trial=(step.trial_kind, step.index))
        else:
            progress = progress.apply(Move.SUBMIT_QUESTIONNAIRE, questionnaire=step.questionnaire)
        phases.append(progress.phase)
    return phases


def test_the_paper_study_goes_consent_instructions_quiz_practice_then_trials_and_questionnaires(plan):
    assert walk(plan) == [Phase.CONSENT, Phase.INSTRUCTIONS, Phase.QUIZ, Phase.PRACTICE] + [
        Phase.TRIAL, Phase.QUESTIONNAIRE] * 4 + [Phase.DONE]
    trials = [s for s in plan if s.kind == "trial"]
    assert [(s.trial_kind, s.index, s.number, s.total) for s in trials] == [
        ("practice", 0, 1, 5), ("main", 0, 2, 5), ("main", 1, 3, 5), ("main", 2, 4, 5), ("main", 3, 5, 5)]
    assert trials[0].robot == "stay" and trials[0].kitchen == "practice"


@pytest.mark.parametrize(("step", "move", "reason"), [(0, Move.DECLINE_CONSENT, "declined_consent"),
                                                     (2, Move.FAIL_QUIZ, "failed_quiz")])
def test_declining_consent_or_failing_the_quiz_screens_out_for_good(plan, step, move, reason):
    out = Progress(plan, step).apply(move)
    assert out.phase is Phase.SCREENED_OUT and out.status == "screened_out"
    assert out.screen_out_reason == reason
    for any_move in Move:
        with pytest.raises(IllegalTransition):
            out.apply(any_move)


def test_a_trial_or_questionnaire_must_be_the_current_one(plan):
    at_practice = Progress(plan, 3)
    with pytest.raises(IllegalTransition, match="current trial"):
        at_practice.apply(Move.END_TRIAL, trial=("main", 0))
    at_questionnaire = Progress(plan, 5)
    assert at_questionnaire.phase is Phase.QUESTIONNAIRE
    with pytest.raises(IllegalTransition, match="current questionnaire"):
        at_questionnaire.apply(Move.SUBMIT_QUESTIONNAIRE, questionnaire="other")


@given(step=st.integers(0, 12), move=st.sampled_from(list(Move)))
def test_only_legal_moves_change_the_state(plan, step, move):
    progress = Progress(plan, step)
    current = progress.current
    legal = {
        Phase.CONSENT: {Move.ACCEPT_CONSENT, Move.DECLINE_CONSENT},
        Phase.INSTRUCTIONS: {Move.FINISH_INSTRUCTIONS},
        Phase.QUIZ: {Move.PASS_QUIZ, Move.FAIL_QUIZ},
        Phase.PRACTICE: {Move.END_TRIAL, Move.SERVER_FULL}, Phase.TRIAL: {Move.END_TRIAL, Move.SERVER_FULL},
        Phase.QUESTIONNAIRE: {Move.SUBMIT_QUESTIONNAIRE}, Phase.DONE: set(),
    }[progress.phase]
    # The current step's trial and questionnaire, so that only the move itself decides (a step that is no trial
    # names none).
    trial = None if current.trial_kind is None or current.index is None else (current.trial_kind, current.index)
    if move in legal:
        after = progress.apply(move, trial=trial, questionnaire=current.questionnaire)
        assert after.step == step + (0 if move in (Move.DECLINE_CONSENT, Move.FAIL_QUIZ, Move.SERVER_FULL) else 1)
    else:
        with pytest.raises(IllegalTransition):
            progress.apply(move, trial=trial, questionnaire=current.questionnaire)


def test_end_of_study_questionnaires_come_once_after_the_last_trial(study_file):
    loaded = load_one(study_file(robots=["stay", "fov_aware"], questionnaires=[
        {"id": "each", "items": [{"id": "a", "text": "A", "scale": {"min": 1, "max": 3}}]},
        {"id": "final", "when": "end_of_study", "items": [{"id": "b", "text": "B", "scale": {"min": 1, "max": 3}}]}]))
    plan = build_plan(loaded.study, loaded.orders[0])
    kinds = [(s.kind, s.questionnaire, s.after_trial) for s in plan]
    assert kinds == [("consent", None, None), ("instructions", None, None), ("trial", None, None),
                     ("questionnaire", "each", 0), ("trial", None, None), ("questionnaire", "each", 1),
                     ("questionnaire", "final", None), ("done", None, None)]


def test_an_abandoned_main_trial_skips_its_questionnaires_and_a_screen_out_keeps_its_reason(plan):
    at_first_main = Progress(plan, 4)
    assert at_first_main.phase is Phase.TRIAL and plan[5].kind == "questionnaire"
    played = at_first_main.apply(Move.END_TRIAL, trial=("main", 0))
    unplayed = at_first_main.apply(Move.END_TRIAL, trial=("main", 0), played=False)
    assert played.phase is Phase.QUESTIONNAIRE
    assert unplayed.phase is Phase.TRIAL and unplayed.current.index == 1, "nobody asks about an unplayed round"
    out = unplayed.screen_out("abandoned_rounds")
    assert out.phase is Phase.SCREENED_OUT and out.status == "screened_out"
    assert out.screen_out_reason == "abandoned_rounds"
    with pytest.raises(IllegalTransition):
        out.screen_out("low_engagement")
