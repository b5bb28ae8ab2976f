"""How long a study takes, computed from the study itself, and the placeholders that put it into the texts
participants read (consent and instructions).

The rounds counted are those one participant plays: the practice rounds and one condition order — with a factor
between participants (``between``), their group's conditions only, never every group's. A round lasts at most
``horizon / tick_rate_hz`` seconds in ``fixed_rate``, and at most the wall-clock limit ``timing.max_round_seconds``
in ``wait_for_participant`` (``Timing.round_seconds``); the pages around the rounds are estimated with the per-page
times below (a reader who does not rush). The total is an upper estimate: rounds end early when every order is
delivered. A participant's page counts their own stored plan (:func:`study_length` with ``rounds``), which is the
same unless the study file was edited after they joined.

Placeholders (written in the consent or instructions Markdown, replaced when the page is shown):

=======================  ==========================================================================
``{minutes}``            the whole study, in minutes, rounded up
``{rounds}``             every round, practice included
``{main_rounds}``        the rounds that count
``{practice_rounds}``    the practice rounds
``{round_time}``         the longest a round lasts, in words ("80 seconds", "2 minutes")
``{questions_per_round}`` the questions asked after each round
``{practice_note}``      "The first round is practice and does not count." (or the plural; empty without practice)
``{clock_note}``         what the clock means for the participant: on ``wait_for_participant`` that the kitchen
                         waits for them (the robot and the steaks move only while their cook acts; "." lets time
                         pass); on ``fixed_rate`` that the kitchen goes on while they think
=======================  ==========================================================================
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable
from dataclasses import dataclass

from study_config.study.models import Study
from study_config.study.questionnaire import Item

CONSENT_SECONDS = 60
INSTRUCTIONS_SECONDS = 180
QUIZ_QUESTION_SECONDS = 20
ROUND_PAGES_SECONDS = 20
"""The intro card and the summary around each round."""
ITEM_SECONDS = {"rating": 8, "choice": 10, "text": 40}
END_SECONDS = 30

PLACEHOLDER = re.compile(r"\{([a-z_]+)\}")


@dataclass(frozen=True, slots=True)
class StudyLength:
    """The study's length as participants are told it."""

    practice_rounds: int
    main_rounds: int
    round_seconds: float
    """The longest a round lasts."""
    questions_per_round: int
    total_seconds: float
    """Every page and every round at full length."""
    waits: bool = False
    """The kitchen waits for the participant (``wait_for_participant``)."""

    @property
    def minutes(self) -> int:
        return max(1, math.ceil(self.total_seconds / 60))

    def placeholders(self) -> dict[str, str]:
        rounds = self.practice_rounds + self.main_rounds
        practice = {0: "", 1: "The first round is practice and does not count."}.get(
            self.practice_rounds, f"The first {self.practice_rounds} rounds are practice and do not count.")
        return {"minutes": str(self.minutes), "rounds": str(rounds), "main_rounds": str(self.main_rounds),
                "practice_rounds": str(self.practice_rounds), "round_time": duration_words(self.round_seconds),
                "questions_per_round": str(self.questions_per_round), "practice_note": practice,
                "clock_note": WAITS_NOTE if self.waits else GOES_ON_NOTE}


WAITS_NOTE = ("The kitchen waits for you: the robot and the steaks move only while your cook moves or works. Choose "
              "your next task when you are ready; to let time pass while a steak cooks, press **.** (stay): each "
              "press moves the kitchen on a moment.")
"""``{clock_note}`` on the paper's clock (``wait_for_participant``)."""
GOES_ON_NOTE = "The robot works on its own, and the kitchen goes on while you think."
"""``{clock_note}`` on ``fixed_rate``."""


def duration_words(seconds: float) -> str:
    """``80`` → "80 seconds", ``120`` → "2 minutes", ``150`` → "2.5 minutes" (participants never see ticks)."""
    if seconds < 120:
        whole = math.ceil(seconds)
        return f"{whole} second{'' if whole == 1 else 's'}"
    minutes = round(seconds / 60, 1)
    return f"{minutes:g} minutes"


def _items_seconds(items: Iterable[Item]) -> float:
    return float(sum(ITEM_SECONDS[item.type] for item in items))


def rounds_per_participant(study: Study) -> tuple[int, int]:
    """The practice and main rounds one participant plays: every practice round and one condition order (with a
    factor between participants, one group's conditions; every order has the same length)."""
    return sum(p.count for p in study.practice), max(len(order) for order in study.condition_orders())


def study_length(study: Study, rounds: tuple[int, int] | None = None) -> StudyLength:
    """The length of ``study`` for one participant from its rounds, horizon, tick rate, quiz and questionnaires;
    ``rounds``: the participant's own (practice, main) rounds, from their plan (default: what the study gives
    each participant, :func:`rounds_per_participant`)."""
    practice, main = rounds if rounds is not None else rounds_per_participant(study)
    round_seconds = study.timing.round_seconds(study.world.horizon)
    after_each = [q for q in study.questionnaires if q.when == "after_each_trial"]
    at_end = [q for q in study.questionnaires if q.when == "end_of_study"]
    questions = sum(len(q.items) for q in after_each)
    total = (CONSENT_SECONDS + INSTRUCTIONS_SECONDS
             + QUIZ_QUESTION_SECONDS * (len(study.quiz.questions) if study.quiz else 0)
             + (practice + main) * (round_seconds + ROUND_PAGES_SECONDS)
             + main * sum(_items_seconds(q.items) for q in after_each)
             + sum(_items_seconds(q.items) for q in at_end) + END_SECONDS)
    return StudyLength(practice, main, round_seconds, questions, total,
                       waits=study.timing.mode == "wait_for_participant")


def fill_placeholders(text: str, values: dict[str, str]) -> str:
    """``text`` with every known ``{name}`` replaced; anything else in braces is left as written."""
    return PLACEHOLDER.sub(lambda m: values.get(m.group(1), m.group(0)), text)


def unknown_placeholders(text: str, values: Iterable[str]) -> list[str]:
    """The ``{name}`` tokens of ``text`` that are not placeholders (likely typos), in order, once each."""
    known = set(values)
    return list(dict.fromkeys(m.group(0) for m in PLACEHOLDER.finditer(text) if m.group(1) not in known))
