"""The participant's REST API (token-scoped after join); every state change answers the new session view.

``POST /api/studies/{study_id}/join`` → token and state (never the condition order: participants are blind);
``POST /api/studies/{study_id}/resume`` (an experimenter's one-time resume link → a token on this device);
``GET /api/session``; ``POST /api/session/device``; ``POST /api/session/consent``;
``POST /api/session/instructions_done``; ``POST /api/session/quiz``; ``POST /api/session/questionnaire``;
``GET /api/session/completion``. Illegal transitions answer 409, invalid answers 422; joins beyond the
per-address limit answer 429 (:mod:`server.security`).
"""

from __future__ import annotations

import time
from typing import Annotated, Any

from anyio import from_thread
from fastapi import APIRouter, Depends, Request

from server.admin.resume import link_secret, read_code, verify
from server.admin.test_links import signing_key, verify_test_code
from server.deps import ParticipantDep, ServicesDep, bearer, is_admin, participant_study, path_study
from server.errors import ApiError
from server.flow import payment, service
from server.flow.handoff import handoff_code, handoff_key
from server.flow.progress import Move
from server.flow.schemas import (
    ConsentRequest,
    JoinRequest,
    JoinResponse,
    QuestionnaireRequest,
    QuizRequest,
    ResumeRequest,
    StudyPublic,
)
from server.flow.views import load_session_view
from server.security import limit_joins
from server.services import Services
from server.text_input import storable_body
from store import participants
from store.tables import ParticipantRow
from study_config.catalog import LoadedStudy
from study_config.study.device import DeviceInfo

router = APIRouter(prefix="/api", tags=["participant"], dependencies=[Depends(storable_body)])
StudyDep = Annotated[LoadedStudy, Depends(participant_study)]


@router.get("/studies/{study_id}")
def study_info(loaded: Annotated[LoadedStudy, Depends(path_study)]) -> StudyPublic:
    study = loaded.study
    return StudyPublic(id=study.id, url_parameters=list(study.recruiting.url_parameters))


@router.post("/studies/{study_id}/join", dependencies=[Depends(limit_joins)])
def join(loaded: Annotated[LoadedStudy, Depends(path_study)], body: JoinRequest, request: Request,
         services: ServicesDep) -> JoinResponse:
    """Join, or come back with the token this browser holds (``Authorization``); a known recruiting id from
    a browser without its token answers ``409 already_started`` (:func:`server.flow.service.join`). A pilot join
    (``pilot``) needs the admin token as the bearer, so no participant can make themselves a pilot (and get the
    pilot's pace); without it, 403 ``pilot_needs_admin``. A test run needs an admin-signed test link
    (``test_link``, :mod:`server.admin.test_links`; 410 ``test_link_invalid`` when expired or altered): the body's
    ``test_run`` is ignored."""
    test_run = False
    if body.test_link is not None:
        if not verify_test_code(signing_key(services.admin_token), body.test_link, loaded.id, time.time()):
            raise ApiError(410, "test_link_invalid",
                           "this test link is no longer valid; make a new one in the admin dashboard")
        test_run = True
    if body.pilot is not None:
        if not is_admin(request, services):
            raise ApiError(403, "pilot_needs_admin", "pilot participants are joined with the admin token")
        joined = service.join(services.store, loaded, body.recruiting, test_run, pilot_pace=body.pilot.pace)
    else:
        joined = service.join(services.store, loaded, body.recruiting, test_run, bearer(request),
                              handoff=body.handoff, handoff_key=handoff_key(services.admin_token))
    return _joined(loaded, joined)


@router.post("/studies/{study_id}/resume", dependencies=[Depends(limit_joins)])
def resume(loaded: Annotated[LoadedStudy, Depends(path_study)], body: ResumeRequest,
           services: ServicesDep) -> JoinResponse:
    """Redeem a resume link made by the experimenter (:mod:`server.admin.resume`): this browser gets a new
    token for the participant (the old browser's game socket is closed at once); 410 ``link_invalid`` for a
    used, expired or altered link."""
    code = read_code(body.code)
    with services.store.transaction() as session:
        row = participants.by_public_id(session, code.public_id) if code is not None else None
        token_hash = row.token_hash if row is not None and row.study_id == loaded.id else None
        participant_id = row.id if row is not None else None
    secret = link_secret(services.admin_token)
    joined = None
    if code is not None and token_hash is not None and participant_id is not None and verify(
            secret, code, token_hash, time.time()):
        joined = service.resume_on_new_device(services.store, participant_id, token_hash)
    if joined is None:
        raise ApiError(410, "link_invalid", "this resume link is no longer valid; please contact the researcher")
    from_thread.run_sync(services.registry.revoke, joined.participant.id)
    return _joined(loaded, joined)


def _joined(loaded: LoadedStudy, joined: service.Joined) -> JoinResponse:
    return JoinResponse(token=joined.token, participant_id=joined.participant.public_id, study_id=loaded.id,
                        state=joined.participant.state, rejoined=joined.rejoined)


def _view(services: Services, loaded: LoadedStudy, participant_id: int) -> dict[str, Any]:
    """The session view, with the hand-off code while the session may move to another device
    (:mod:`server.flow.handoff`)."""
    connected = from_thread.run_sync(services.registry.connected)
    with services.store.transaction() as session:
        view = load_session_view(session, loaded, participant_id, connected)
        row = session.get(ParticipantRow, participant_id)
        if row is not None and service.claimable(row):
            view["handoff"] = {"code": handoff_code(handoff_key(services.admin_token), row.public_id, row.token_hash)}
        return view


@router.get("/session")
def get_session(participant: ParticipantDep, loaded: StudyDep, services: ServicesDep) -> dict[str, Any]:
    return _view(services, loaded, participant.id)


@router.post("/session/device")
def device(body: DeviceInfo, participant: ParticipantDep, loaded: StudyDep, services: ServicesDep) -> dict[str, Any]:
    """What the browser reports about its device on landing; the session view's ``device`` says whether it
    may take part."""
    service.record_device(services.store, loaded, participant.id, body)
    return _view(services, loaded, participant.id)


@router.post("/session/consent")
def consent(body: ConsentRequest, participant: ParticipantDep, loaded: StudyDep,
            services: ServicesDep) -> dict[str, Any]:
    service.move(services.store, participant.id, Move.ACCEPT_CONSENT if body.accept else Move.DECLINE_CONSENT)
    return _view(services, loaded, participant.id)


@router.post("/session/instructions_done")
def instructions_done(participant: ParticipantDep, loaded: StudyDep, services: ServicesDep) -> dict[str, Any]:
    service.move(services.store, participant.id, Move.FINISH_INSTRUCTIONS)
    return _view(services, loaded, participant.id)


@router.post("/session/quiz")
def quiz(body: QuizRequest, participant: ParticipantDep, loaded: StudyDep, services: ServicesDep) -> dict[str, Any]:
    """One attempt at the comprehension quiz: the session view with ``quiz_result`` (passed, attempts left,
    the questions answered wrongly with their explanations)."""
    result = service.submit_quiz(services.store, loaded, participant.id, body.answers)
    return {**_view(services, loaded, participant.id), "quiz_result": result.to_dict()}


@router.post("/session/questionnaire")
def questionnaire(body: QuestionnaireRequest, participant: ParticipantDep, loaded: StudyDep,
                  services: ServicesDep) -> dict[str, Any]:
    service.submit_questionnaire(services.store, loaded, participant.id, body.questionnaire_id, body.answers)
    return _view(services, loaded, participant.id)


@router.get("/session/completion")
def completion(participant: ParticipantDep, loaded: StudyDep) -> dict[str, Any]:
    return payment.shown_to(participant, service.completion(loaded, participant))
