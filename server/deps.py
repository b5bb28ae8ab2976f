"""FastAPI dependencies: the services made at start-up, the participant behind a token, the admin check.

Participant tokens come as ``Authorization: Bearer <token>`` or, for the websocket (browsers cannot set
headers there), as the subprotocol ``token.<token>`` offered beside ``steakhouse.v1`` (what the browser
client does: the token stays out of URLs, so out of proxy and server access logs), or as ``?token=<token>``
(for scripts). The admin token only as a bearer header. Unknown, missing or wrong tokens all give the same
401 with no detail.
"""

from __future__ import annotations

import secrets
from typing import Annotated

from fastapi import Depends, Path
from starlette.requests import HTTPConnection

from server.errors import ApiError, unauthorized
from server.services import Services
from store import participants
from store.engine import Store
from store.tables import ParticipantRow
from study_config.catalog import LoadedStudy


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


SUBPROTOCOL = "steakhouse.v1"
"""The websocket subprotocol the server selects when a client offers it."""
TOKEN_SUBPROTOCOL_PREFIX = "token."


def offered_subprotocols(conn: HTTPConnection) -> list[str]:
    header = conn.headers.get("sec-websocket-protocol", "")
    return [part.strip() for part in header.split(",") if part.strip()]


def subprotocol_token(conn: HTTPConnection) -> str | None:
    for offered in offered_subprotocols(conn):
        if offered.startswith(TOKEN_SUBPROTOCOL_PREFIX) and len(offered) > len(TOKEN_SUBPROTOCOL_PREFIX):
            return offered[len(TOKEN_SUBPROTOCOL_PREFIX):]
    return None


def participant_token(conn: HTTPConnection) -> str | None:
    return bearer(conn) or subprotocol_token(conn) or conn.query_params.get("token") or None


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


def is_admin(conn: HTTPConnection, services: Services) -> bool:
    token = bearer(conn)
    return token is not None and secrets.compare_digest(token.encode(), services.admin_token.encode())


def require_admin(conn: HTTPConnection, services: ServicesDep) -> None:
    if not is_admin(conn, services):
        raise unauthorized()
