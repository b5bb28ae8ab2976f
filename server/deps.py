"""FastAPI dependencies: the services made at start-up, the participant behind a token, the admin check.

Participant tokens come as ``Authorization: Bearer <token>`` or, for the websocket (browsers cannot set
headers there), as ``?token=<token>``. The admin token only as a bearer header. Unknown, missing or wrong
tokens all give the same 401 with no detail.
"""

from __future__ import annotations

import secrets
from typing import Annotated

from fastapi import Depends, Path
from starlette.requests import HTTPConnection

from server.catalog import LoadedStudy
from server.errors import ApiError, unauthorized
from server.services import Services
from server.store import participants
from server.store.engine import Store
from server.store.tables import ParticipantRow


def get_services(conn: HTTPConnection) -> Services:
    services: Services = conn.app.state.services
    return services


ServicesDep = Annotated[Services, Depends(get_services)]


def bearer(conn: HTTPConnection) -> str | None:
    header = conn.headers.get("authorization", "")
    scheme, _, value = header.partition(" ")
    if scheme.lower() == "bearer" and value.strip():
        return value.strip()
    return None


def participant_token(conn: HTTPConnection) -> str | None:
    return bearer(conn) or conn.query_params.get("token") or None


def find_participant(store: Store, token: str) -> ParticipantRow | None:
    if len(token) > 200:
        return None
    with store.transaction() as session:
        return participants.by_token(session, token)


def current_participant(conn: HTTPConnection, services: ServicesDep) -> ParticipantRow:
    token = participant_token(conn)
    row = find_participant(services.store, token) if token else None
    if row is None:
        raise unauthorized()
    return row


ParticipantDep = Annotated[ParticipantRow, Depends(current_participant)]


def participant_study(participant: ParticipantDep, services: ServicesDep) -> LoadedStudy:
    loaded = services.catalog.get(participant.study_id)
    if loaded is None:
        raise ApiError(410, "study_gone", "this study is no longer served")
    return loaded


def path_study(study_id: Annotated[str, Path(max_length=64)], services: ServicesDep) -> LoadedStudy:
    loaded = services.catalog.get(study_id)
    if loaded is None:
        raise ApiError(404, "unknown_study", "no such study")
    return loaded


def require_admin(conn: HTTPConnection, services: ServicesDep) -> None:
    token = bearer(conn)
    if token is None or not secrets.compare_digest(token.encode(), services.admin_token.encode()):
        raise unauthorized()
