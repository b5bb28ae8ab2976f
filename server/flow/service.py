"""The participant operations behind the REST API and the game: each one transaction over the store.

- :func:`join`: least-filled condition order (see :mod:`store.assignment`), plan, token. A recruiting
  id (the study's first URL parameter, e.g. ``PROLIFIC_PID``) is not a password: a second join with it
  answers the same participant only from the browser holding that participant's token (the token is kept);
  from any other browser it is refused (``409 already_started``), the attempt stored as a ``join_refused``
  event, and the participant's session and token are left as they were. Never two assignments. Ids are
  compared by their key (:mod:`store.recruit_ids`: case, spaces, invisible characters, diacritics and look-alike
  letters of other scripts do not make another person). The
  exception is a session that holds nothing yet: its device was refused on landing and it has not moved past
  the first step (a phone user sent to a laptop): a browser with the id **and the hand-off code its first device
  shows** (:mod:`server.flow.handoff`) claims it (a new token, the phone's stops working, a ``session_claimed``
  event); with the id alone it is refused (``409 handoff_code_required``). A study with
  ``recruiting.require_id`` refuses a join without the id (``422 recruit_id_required``), except test runs.
- :func:`resume_on_new_device`: the experimenter's one-time resume link redeemed (:mod:`server.admin.resume`):
  a fresh token for the participant, the old one stops working.
- :func:`move`: one state-machine transition, applied only if nobody moved the participant meanwhile.
- :func:`submit_questionnaire`: answers checked, stored and the transition made, all or nothing.
- :func:`submit_quiz`: one attempt at the comprehension quiz stored; passed → the next step, the last allowed
  attempt failed → screened out.
- :func:`record_device`: the device the browser reported, stored with the participant (and as an event, within the
  participant's row budget: :mod:`store.budget`).
- :func:`end_trial`: the trial row ended, the participant's activity in it counted and judged
  (:mod:`server.flow.engagement`), and the participant moved past it (or screened out when they did not take
  part, :mod:`server.flow.standing`), together.
"""

from __future__ import annotations

import logging
import secrets
import uuid
from dataclasses import dataclass
from typing import Any

from sqlalchemy import func, select
from sqlalchemy.exc import IntegrityError
from sqlalchemy.orm import Session

from server.errors import AnswerProblems, ApiError
from server.flow import standing
from server.flow.answers import check_answers, stored_answer
from server.flow.engagement import engagement_problem
from server.flow.handoff import MAX_WRONG, matches
from server.flow.plan import build_plan, plan_from_json, plan_to_json
from server.flow.progress import IllegalTransition, Move, Phase, Progress
from server.flow.quiz import QuizResult, quiz_problems
from store import activity, assignment, budget, lease, participants, trials
from store.engine import Store
from store.group_assignment import least_filled_grouped
from store.recruit_ids import recruit_key
from store.tables import AnswerRow, AssignmentRow, EventRow, ParticipantRow, QuizAttemptRow
from store.types import utcnow
from study_config.catalog import LoadedStudy
from study_config.study import Study
from study_config.study.device import DeviceInfo, device_problems
from study_config.study.device import refused as device_refused

log = logging.getLogger(__name__)

ALREADY_STARTED = ("this ID has already started in another browser; continue there, or contact the "
                   "researcher")


@dataclass(frozen=True)
class Refused:
    """A join with a recruiting id that already started elsewhere: the participant it belongs to, and why (the
    409's code and message)."""

    participant: ParticipantRow
    code: str = "already_started"
    message: str = ALREADY_STARTED


HANDOFF_REQUIRED = ("this ID started on another device: type the code that device shows (or open the link it "
                    "shows) to continue here")
HANDOFF_WRONG = "this is not the code your other device shows; check it and try again"
HANDOFF_LOCKED = "too many wrong codes: please contact the researcher to continue on this device"


@dataclass(frozen=True)
class Joined:
    token: str
    participant: ParticipantRow
    assignment: AssignmentRow
    rejoined: bool


def progress_of(row: ParticipantRow) -> Progress:
    return Progress(plan_from_json(row.plan), row.step, screened_out=row.status == "screened_out",
                    reason=row.screen_out_reason)


def join(store: Store, loaded: LoadedStudy, recruiting: dict[str, str], test_run: bool,
         presented_token: str | None = None, pilot_pace: str | None = None, handoff: str | None = None,
         handoff_key: bytes = b"") -> Joined:
    """Join ``loaded``'s study, or come back to it: ``presented_token`` is the token the browser already holds
    (its ``Authorization`` header), which alone resumes a participant whose recruiting id is known; ``handoff``
    (checked with ``handoff_key``) is the code a device-refused session's first device shows. A pilot
    participant (``pilot_pace`` given; the route lets only the admin ask for it) is balanced among pilots, and
    the admin's pilot driver resumes its own pilot by recruiting id (with a new token)."""
    study = loaded.study
    names = study.recruiting.url_parameters
    kept = {name: recruiting[name] for name in names if name in recruiting}
    key = recruit_key(kept.get(names[0])) if names else None
    if key is None and study.recruiting.require_id and not (test_run or study.test_run or pilot_pace):
        raise ApiError(422, "recruit_id_required", "this study is joined from its link on the recruiting platform, "
                       f"which carries your {names[0]}; please open that link again")
    with store.transaction() as session:
        assignment.lock_study(session, study.id)
        outcome = _join_in(session, loaded, kept, key, test_run, presented_token, pilot_pace,
                           (handoff, handoff_key) if handoff else None)
    if isinstance(outcome, Refused):
        log.warning("join refused (%s): the recruiting id of participant %s already started in another browser",
                    outcome.code, outcome.participant.public_id)
        raise ApiError(409, outcome.code, outcome.message)
    return outcome


def _rejoined(session: Session, row: ParticipantRow, token: str) -> Joined:
    found = participants.assignment_of(session, row.id)
    if found is None:
        raise ApiError(500, "internal", "participant without assignment")
    return Joined(token, row, found, rejoined=True)


def _join_in(session: Session, loaded: LoadedStudy, kept: dict[str, str], key: str | None, test_run: bool,
             presented_token: str | None, pilot_pace: str | None,
             handoff: tuple[str, bytes] | None = None) -> Joined | Refused:
    """``key``: the recruiting id's key (``store.recruit_ids``), ``None`` without one; ``handoff``: a typed hand-off
    code and the key it is checked with."""
    study = loaded.study
    pilot = pilot_pace is not None
    if key:
        existing = participants.by_recruit_key(session, study.id, key)
        if existing is not None and existing.pilot != pilot:
            raise ApiError(409, "recruit_id_taken", "this recruiting id belongs to a pilot participant"
                           if existing.pilot else "this recruiting id belongs to a real participant")
        if existing is not None and pilot:  # the admin's pilot driver resumes its pilot with a new token
            token = secrets.token_urlsafe(32)
            participants.rotate_token(session, existing.id, token)
            return _rejoined(session, existing, token)
        if existing is not None:
            holder = participants.by_token(session, presented_token) if presented_token else None
            other_browser = presented_token is None or holder is None or holder.id != existing.id
            if other_browser and claimable(existing):
                return _hand_off(session, existing, handoff)
            if other_browser or presented_token is None:
                budget.store_or_count(session, EventRow(
                    participant_id=existing.id, trial_id=None, tick=None, kind="join_refused",
                    payload={"reason": "already_started", "had_token": presented_token is not None},
                    created_at=utcnow()), budget.REFUSED_JOINS)
                return Refused(existing)
            return _rejoined(session, existing, presented_token)
    token = secrets.token_urlsafe(32)
    counts = assignment.order_counts(session, study.id, len(loaded.orders), utcnow(),
                                     study.assignment.in_progress_window_minutes, pilot=pilot)
    index = least_filled_grouped(counts, loaded.order_groups)
    order = list(loaded.orders[index])
    plan = build_plan(study, order)
    row = participants.create(
        session, study_id=study.id, public_id=uuid.uuid4().hex, token=token,
        recruit_id=kept[study.recruiting.url_parameters[0]] if key else None, recruit_key=key,
        recruiting=kept, config_hash=study.config_hash(), plan=plan_to_json(plan),
        state=Progress(plan, 0).phase.value, test_run=test_run or study.test_run, order_index=index,
        condition_order=order, pilot_pace=pilot_pace)
    found = participants.assignment_of(session, row.id)
    if found is None:
        raise ApiError(500, "internal", "assignment not stored")
    return Joined(token, row, found, rejoined=False)


def claimable(row: ParticipantRow) -> bool:
    """A session that holds nothing yet: its device was refused on landing and it is still at its first step."""
    return row.status == "in_progress" and row.step == 0 and device_refused(row.device)


def _hand_off(session: Session, row: ParticipantRow, handoff: tuple[str, bytes] | None) -> Joined | Refused:
    """Another browser asks for a claimable session: only with the hand-off code its first device shows."""
    wrong = int(session.scalar(select(func.count()).select_from(EventRow).where(
        EventRow.participant_id == row.id, EventRow.kind == "handoff_refused")) or 0)
    if wrong >= MAX_WRONG:
        return Refused(row, "handoff_locked", HANDOFF_LOCKED)
    if handoff is None:
        return Refused(row, "handoff_code_required", HANDOFF_REQUIRED)
    typed, key = handoff
    if not matches(key, typed, row.public_id, row.token_hash):
        session.add(EventRow(participant_id=row.id, trial_id=None, tick=None, kind="handoff_refused",
                             payload={"wrong": wrong + 1}, created_at=utcnow()))
        return Refused(row, "handoff_code_wrong", HANDOFF_WRONG)
    return _claimed(session, row)


def _claimed(session: Session, row: ParticipantRow) -> Joined:
    token = secrets.token_urlsafe(32)
    participants.rotate_token(session, row.id, token)
    session.add(EventRow(participant_id=row.id, trial_id=None, tick=None, kind="session_claimed",
                         payload={"refused_device": row.device}, created_at=utcnow()))
    log.info("participant %s continues in a new browser (their first device was refused)", row.public_id)
    return _rejoined(session, row, token)


def resume_on_new_device(store: Store, participant_id: int, expected_token_hash: str) -> Joined | None:
    """Give the participant a fresh token (their old browser's stops working), if their token is still the one
    the resume link was made for (so a link works once); ``None`` otherwise."""
    token = secrets.token_urlsafe(32)
    with store.transaction() as session:
        row = _load(session, participant_id)
        if not secrets.compare_digest(row.token_hash, expected_token_hash):
            return None
        participants.rotate_token(session, row.id, token)
        session.add(EventRow(participant_id=row.id, trial_id=None, tick=None, kind="resume_link_used",
                             payload={}, created_at=utcnow()))
        return _rejoined(session, row, token)


def _apply(session: Session, row: ParticipantRow, progress: Progress, new: Progress, move_: Move) -> None:
    moved = participants.advance(session, row.id, from_step=progress.step, to_step=new.step,
                                 state=new.phase.value, status=new.status, screen_out_reason=new.reason)
    if not moved:
        raise IllegalTransition(progress.phase, move_, "the participant was moved by another request")


def move(store: Store, participant_id: int, move_: Move) -> Progress:
    """Apply ``move_`` (consent, instructions) to the participant's current state."""
    with store.transaction() as session:
        row = _load(session, participant_id)
        progress = progress_of(row)
        new = progress.apply(move_)
        _apply(session, row, progress, new, move_)
        return new


def submit_questionnaire(store: Store, loaded: LoadedStudy, participant_id: int, questionnaire_id: str,
                         answers: dict[str, Any]) -> Progress:
    with store.transaction() as session:
        row = _load(session, participant_id)
        progress = progress_of(row)
        new = progress.apply(Move.SUBMIT_QUESTIONNAIRE, questionnaire=questionnaire_id)
        questionnaire = next((q for q in loaded.study.questionnaires if q.id == questionnaire_id), None)
        if questionnaire is None:
            raise ApiError(409, "unknown_questionnaire", f"questionnaire {questionnaire_id!r} is not in the study")
        problems = check_answers(questionnaire, answers)
        if problems:
            raise AnswerProblems(problems)
        step = progress.current
        trial = (trials.latest_attempt(session, row.id, "main", step.after_trial)
                 if step.after_trial is not None else None)
        now = utcnow()
        for item in questionnaire.items:
            value, text = stored_answer(item, answers.get(item.id))
            session.add(AnswerRow(participant_id=row.id, questionnaire_id=questionnaire.id, step=progress.step,
                                  after_trial=step.after_trial, trial_id=trial.id if trial else None,
                                  item_id=item.id, value=value, text=text, created_at=now))
        _apply(session, row, progress, new, Move.SUBMIT_QUESTIONNAIRE)
        return new


def submit_quiz(store: Store, loaded: LoadedStudy, participant_id: int, answers: dict[str, Any]) -> QuizResult:
    """Store one attempt at the quiz (every question answered, or 422 and nothing stored) and move on."""
    quiz = loaded.study.quiz
    with store.transaction() as session:
        row = _load(session, participant_id)
        progress = progress_of(row)
        if quiz is None or progress.phase is not Phase.QUIZ:
            raise IllegalTransition(progress.phase, Move.PASS_QUIZ)
        problems = quiz_problems(quiz, answers)
        if problems:
            raise AnswerProblems(problems)
        attempt = quiz_attempts(session, row.id) + 1
        wrong = quiz.wrong(answers)
        session.add(QuizAttemptRow(participant_id=row.id, attempt=attempt, answers=dict(answers),
                                   wrong=[q.id for q in wrong], passed=not wrong, created_at=utcnow()))
        try:
            session.flush()
        except IntegrityError as exc:  # the same attempt submitted twice at once (two tabs)
            raise IllegalTransition(progress.phase, Move.PASS_QUIZ, "the attempt was already submitted") from exc
        if not wrong:
            _apply(session, row, progress, progress.apply(Move.PASS_QUIZ), Move.PASS_QUIZ)
        elif attempt >= quiz.max_attempts:
            _apply(session, row, progress, progress.apply(Move.FAIL_QUIZ), Move.FAIL_QUIZ)
        return QuizResult(not wrong, attempt, max(quiz.max_attempts - attempt, 0) if wrong else 0,
                          {q.id: q.explanation for q in wrong})


def quiz_attempts(session: Session, participant_id: int) -> int:
    """How many times the participant submitted the quiz."""
    found = session.scalar(select(func.count()).select_from(QuizAttemptRow)
                           .where(QuizAttemptRow.participant_id == participant_id))
    return int(found or 0)


def record_device(store: Store, loaded: LoadedStudy, participant_id: int, info: DeviceInfo) -> list[str]:
    """Store what the browser reported about its device and what stops it taking part (none: it may)."""
    problems: list[str] = list(device_problems(loaded.study.device, info))
    now = utcnow()
    report = {**info.model_dump(), "problems": problems, "checked_at": now.isoformat()}
    with store.transaction() as session:
        row = _load(session, participant_id)
        row.device = report
        standing.review_device(row, problems)
        budget.store_or_count(session, EventRow(participant_id=row.id, trial_id=None, tick=None, kind="device_check",
                                                payload=report, created_at=now), budget.DEVICE_REPORTS, now)
    return problems


def end_trial_in(session: Session, participant_id: int, trial_id: int, kind: str, index: int, *, status: str,
                 reason: str, ticks: int | None = None, delivered: int | None = None,
                 score: int | None = None, study: Study | None = None, epoch: int | None = None,
                 end_event: dict[str, Any] | None = None) -> Progress | None:
    """End the trial row and move the participant past the trial (inside ``session``'s transaction).

    ``epoch``: the ender's lease on the round (``store.lease``); the end is refused when another process has
    taken the round over since. Without one (the sweep, a reconnection after the grace window) the lease is
    voided first, so that whoever held it stores nothing more. ``end_event``: the ``trial_end`` event's payload,
    stored with the end under its epoch (only when the end is stored, so a round ends once, with one event).

    With the ``study``, the participant's activity in the trial is counted and stored, a finished main trial is
    judged for engagement (unless the robot's health made it invalid: a broken robot's round says nothing about
    the participant), and after a main trial the participant's standing is reviewed: they stop counting
    toward their order when a round cannot become a cell, and are screened out when they did not take part
    (:mod:`server.flow.standing`). Without it (tools that build a store by hand) only the trial ends.

    Returns the participant's new progress, or ``None`` if the trial had already ended or its lease had passed.
    """
    row = _load(session, participant_id, lock=True)  # the participant first, then the trial (as prepare_trial)
    if epoch is None:
        epoch = lease.fence(session, trial_id)
    if not trials.end(session, trial_id, status=status, reason=reason, ticks=ticks, delivered=delivered,
                      score=score, epoch=epoch):
        return None
    if end_event is not None:
        session.add(EventRow(participant_id=row.id, trial_id=trial_id, tick=ticks, kind="trial_end",
                             payload=end_event, created_at=utcnow(), epoch=epoch))
    screen_out = None
    if study is not None:
        session.flush()
        done = activity.measure(session, trial_id, study.timing.tick_rate_hz)
        judged = kind == "main" and status == trials.FINISHED and not trials.robot_invalid(session, trial_id)
        problem = (engagement_problem(done, study.validity, standing.earlier_choices(session, participant_id, index))
                   if judged else None)
        activity.record(session, trial_id, done, problem.text() if problem else None)
        if problem is not None:
            log.warning("trial %d (participant %s) is low-engagement: %s", trial_id, row.public_id, problem.text())
            session.add(EventRow(participant_id=row.id, trial_id=trial_id, tick=ticks, kind="trial_low_engagement",
                                 payload={**problem.to_dict(), "round": index + 1}, created_at=utcnow(),
                                 epoch=epoch))
        if kind == "main":
            session.flush()
            screen_out = standing.review_rounds(session, row, study.validity)
    progress = progress_of(row)
    try:
        new = progress.apply(Move.END_TRIAL, trial=(kind, index), played=status != trials.ABANDONED)
    except IllegalTransition:
        return progress
    if screen_out is not None:
        new = new.screen_out(screen_out)
        log.warning("participant %s screened out after main round %d: %s", row.public_id, index + 1, screen_out)
    _apply(session, row, progress, new, Move.END_TRIAL)
    return new


def end_trial(store: Store, participant_id: int, trial_id: int, kind: str, index: int,
              **outcome: Any) -> Progress | None:
    """:func:`end_trial_in` in a transaction of its own."""
    with store.transaction() as session:
        return end_trial_in(session, participant_id, trial_id, kind, index, **outcome)


def completion(loaded: LoadedStudy, row: ParticipantRow) -> dict[str, Any]:
    """The end page's code and redirect; 409 until the participant is done or screened out."""
    recruiting = loaded.study.recruiting
    if row.status == "completed":
        return {"kind": "completion", "code": recruiting.completion_code,
                "redirect_url": recruiting.redirect("completion"), "reason": None}
    if row.status == "screened_out":
        return {"kind": "screen_out", "code": recruiting.screen_out_code,
                "redirect_url": recruiting.redirect("screen_out"), "reason": progress_of(row).screen_out_reason}
    raise ApiError(409, "not_finished", f"the session is in state {row.state!r}, not finished")


def _load(session: Session, participant_id: int, lock: bool = False) -> ParticipantRow:
    # FOR NO KEY UPDATE on PostgreSQL: a batch inserting this participant's events (their foreign key takes FOR KEY
    # SHARE) must not wait on it while holding the trial row this transaction waits for (a deadlock).
    row = session.get(ParticipantRow, participant_id, populate_existing=True,
                      with_for_update={"key_share": True} if lock else None)
    if row is None:
        raise ApiError(404, "not_found", "no such participant")
    return row
