"""The participant's progress as an explicit state machine (STYLE 8): illegal transitions are refused.

States (what the participant is shown now): ``consent`` (just joined) → ``instructions`` → ``quiz`` (when the
study has one) → ``practice`` (one state per practice trial) → ``trial`` and ``questionnaire`` alternating →
``done``; declining consent, or failing the quiz too often, leads to ``screened_out``. Transitions:

=================  ============================  ====================================
action             legal in                      leads to
=================  ============================  ====================================
accept_consent     consent                       the next step (instructions)
decline_consent    consent                       screened_out
finish_instructions instructions                 the next step
pass_quiz          quiz                          the next step
fail_quiz          quiz                          screened_out (the last allowed attempt failed)
end_trial          practice / trial (same trial) the next step (finished or abandoned; after an abandoned main
                                                 trial, past its questionnaires: nobody asks about an unplayed round)
server_full        practice / trial              screened_out (waited too long for a free slot)
submit_questionnaire questionnaire (same id)     the next step
=================  ============================  ====================================

A main trial can also end with a screen-out (``server.flow.standing``: abandoned or low-engagement main rounds
beyond the study's ``validity.max_invalid_rounds``): :meth:`Progress.screen_out` with the reason
``abandoned_rounds`` or ``low_engagement``.

``done`` and ``screened_out`` are final. Any other action raises :class:`IllegalTransition` (HTTP 409).
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

from server.errors import Conflict
from server.flow.plan import Step


class Phase(str, Enum):
    CONSENT = "consent"
    INSTRUCTIONS = "instructions"
    QUIZ = "quiz"
    PRACTICE = "practice"
    TRIAL = "trial"
    QUESTIONNAIRE = "questionnaire"
    DONE = "done"
    SCREENED_OUT = "screened_out"


class Move(str, Enum):
    ACCEPT_CONSENT = "accept_consent"
    DECLINE_CONSENT = "decline_consent"
    FINISH_INSTRUCTIONS = "finish_instructions"
    PASS_QUIZ = "pass_quiz"
    FAIL_QUIZ = "fail_quiz"
    END_TRIAL = "end_trial"
    SUBMIT_QUESTIONNAIRE = "submit_questionnaire"
    SERVER_FULL = "server_full"


_LEGAL: dict[Phase, frozenset[Move]] = {
    Phase.CONSENT: frozenset({Move.ACCEPT_CONSENT, Move.DECLINE_CONSENT}),
    Phase.INSTRUCTIONS: frozenset({Move.FINISH_INSTRUCTIONS}),
    Phase.QUIZ: frozenset({Move.PASS_QUIZ, Move.FAIL_QUIZ}),
    Phase.PRACTICE: frozenset({Move.END_TRIAL, Move.SERVER_FULL}),
    Phase.TRIAL: frozenset({Move.END_TRIAL, Move.SERVER_FULL}),
    Phase.QUESTIONNAIRE: frozenset({Move.SUBMIT_QUESTIONNAIRE}),
    Phase.DONE: frozenset(),
    Phase.SCREENED_OUT: frozenset(),
}

STATUS_IN_PROGRESS = "in_progress"
STATUS_COMPLETED = "completed"
STATUS_SCREENED_OUT = "screened_out"


class IllegalTransition(Conflict):
    """An action the participant's current state does not allow."""

    code = "illegal_transition"

    def __init__(self, phase: Phase, move: Move, reason: str = "") -> None:
        self.phase, self.move = phase, move
        detail = f": {reason}" if reason else ""
        super().__init__(f"cannot {move.value} in state {phase.value}{detail}",
                         {"state": phase.value, "action": move.value})


@dataclass(frozen=True, slots=True)
class Progress:
    """Where a participant is in their plan; :meth:`apply` returns the progress after a legal move."""

    plan: tuple[Step, ...]
    step: int
    screened_out: bool = False
    reason: str | None = None
    """Why a participant was screened out after a round (``participants.screen_out_reason``); ``None``: the
    reason follows from the step they stopped at."""

    def __post_init__(self) -> None:
        if not 0 <= self.step < len(self.plan):
            raise ValueError(f"step {self.step} outside the plan of {len(self.plan)} steps")

    @property
    def current(self) -> Step:
        return self.plan[self.step]

    @property
    def phase(self) -> Phase:
        if self.screened_out:
            return Phase.SCREENED_OUT
        step = self.current
        if step.kind == "trial":
            return Phase.PRACTICE if step.trial_kind == "practice" else Phase.TRIAL
        return Phase(step.kind)

    @property
    def screen_out_reason(self) -> str | None:
        """Why a screened-out participant ended: ``declined_consent``, ``failed_quiz``, ``server_full`` (no
        slot for their round in time, ``server.game.admission``), ``abandoned_rounds`` or ``low_engagement``
        (they did not take part in their rounds, ``server.flow.standing``)."""
        if not self.screened_out:
            return None
        if self.reason is not None:
            return self.reason
        return {"consent": "declined_consent", "quiz": "failed_quiz", "trial": "server_full"}.get(
            self.current.kind, "screened_out")

    @property
    def status(self) -> str:
        if self.screened_out:
            return STATUS_SCREENED_OUT
        return STATUS_COMPLETED if self.phase is Phase.DONE else STATUS_IN_PROGRESS

    def screen_out(self, reason: str) -> Progress:
        """The participant screened out where they are now, for ``reason`` (see :attr:`screen_out_reason`)."""
        if self.screened_out:
            raise IllegalTransition(self.phase, Move.END_TRIAL, "already screened out")
        return Progress(self.plan, self.step, screened_out=True, reason=reason)

    def apply(self, move: Move, *, trial: tuple[str, int] | None = None,
              questionnaire: str | None = None, played: bool = True) -> Progress:
        """The progress after ``move``; ``trial`` is ``(kind, index)`` for ``end_trial``, ``questionnaire``
        the id for ``submit_questionnaire`` (both must name the current step); ``played=False``: the main trial
        ending was abandoned, so the questionnaires about it are skipped."""
        phase = self.phase
        if move not in _LEGAL[phase]:
            raise IllegalTransition(phase, move)
        step = self.current
        if move is Move.END_TRIAL and trial != (step.trial_kind, step.index):
            raise IllegalTransition(phase, move, f"the current trial is {step.trial_kind} {step.index}")
        if move is Move.SUBMIT_QUESTIONNAIRE and questionnaire != step.questionnaire:
            raise IllegalTransition(phase, move, f"the current questionnaire is {step.questionnaire!r}")
        if move in (Move.DECLINE_CONSENT, Move.FAIL_QUIZ, Move.SERVER_FULL):
            return Progress(self.plan, self.step, screened_out=True)
        following = self.step + 1
        if move is Move.END_TRIAL and not played and step.trial_kind == "main":
            while (following < len(self.plan) - 1 and self.plan[following].kind == "questionnaire"
                   and self.plan[following].after_trial == step.index):
                following += 1
        return Progress(self.plan, following)
