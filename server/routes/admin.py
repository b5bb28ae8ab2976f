"""The admin API under ``/api/admin/`` (bearer token from ``STEAKHOUSE_ADMIN_TOKEN``; 401 without it).

Studies with the fill of each condition order and their recruiting links, participants with progress, flags and
questionnaire answers, setting flags, one-time resume links (a participant moving to a new device), live trials
(summary and the full spectator view with the scene the dashboard draws), stored trials, their ticks and events,
and their frames for the replay viewer, and the robot worker pool. The logic lives in ``server.admin`` and
``store``; these routes only wire it.
"""

from __future__ import annotations

import asyncio
import time
from datetime import UTC, datetime, timedelta
from typing import Annotated, Any

from fastapi import APIRouter, Depends, Path, Query, Request
from pydantic import BaseModel, ConfigDict, Field

from server.admin.answers import participant_answers
from server.admin.links import study_links
from server.admin.live import live_view
from server.admin.replay import replay
from server.admin.resume import link_secret, make_code, resume_path
from server.admin.stored_live import running_elsewhere, stored_live_view, stored_summary
from server.admin.test_links import signing_key
from server.deps import ServicesDep, path_study, require_admin
from server.errors import ApiError
from server.game.ownership import process_name
from server.services import Services
from server.text_input import storable_body
from store import participants, trials
from store.overview import (
    invalid_trial_counts,
    low_engagement_counts,
    order_breakdown,
    participant_names,
    participant_public,
    trial_public,
)
from store.tables import EventRow, TrialRow
from store.types import utcnow
from study_config.catalog import LoadedStudy
from study_config.study.warnings import study_warnings

router = APIRouter(prefix="/api/admin", tags=["admin"],
                   dependencies=[Depends(require_admin), Depends(storable_body)])

STORE_INT_MAX = 2**63 - 1
TrialId = Annotated[int, Path(ge=1, le=STORE_INT_MAX)]
"""A trial's id: a positive 64-bit integer (the store's key); anything else is a 422 naming ``trial_id``."""
PublicId = Annotated[str, Path(min_length=1, max_length=64)]
"""A participant's public id (a 32-character hex string)."""
TickStart = Annotated[int, Query(ge=0, le=STORE_INT_MAX)]


class FlagsRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")

    test_run: bool | None = None
    excluded: bool | None = None
    reason: str | None = Field(default=None, max_length=1000)


@router.get("/studies")
def studies(services: ServicesDep) -> list[dict[str, Any]]:
    out = []
    now = utcnow()
    with services.store.transaction() as session:
        for loaded in services.catalog:
            study = loaded.study
            fill = order_breakdown(session, study.id, len(loaded.orders), now,
                                   study.assignment.in_progress_window_minutes)
            for cell, order in zip(fill, loaded.orders, strict=True):
                cell["conditions"] = list(order)  # type: ignore[assignment]
            out.append({"id": study.id, "title": study.title, "config_hash": study.config_hash(),
                        "conditions": [c.id for c in study.conditions], "orders": fill,
                        "timing": study.timing.model_dump(), "notes": study.notes,
                        "warnings": [w.to_dict() for w in study_warnings(study)],
                        "live_trials": sum(1 for g in services.registry.games.values() if g.meta.study_id == study.id)
                        + len(running_elsewhere(session, [study.id], set(services.registry.games),
                                                _live_since(services)))})
    return out


@router.get("/studies/{study_id}/links")
def links(request: Request, loaded: Annotated[LoadedStudy, Depends(path_study)], services: ServicesDep
          ) -> dict[str, Any]:
    """The study's recruiting links, with test-run links signed now (``server.admin.test_links``)."""
    return study_links(loaded, str(request.base_url), signing_key(services.admin_token))


@router.get("/participants")
def list_participants(services: ServicesDep, study_id: Annotated[str | None, Query(max_length=64)] = None,
                      ) -> list[dict[str, Any]]:
    with services.store.transaction() as session:
        rows = participants.list_participants(session, study_id)
        ids = {p.id for p, _ in rows}
        invalid, low = invalid_trial_counts(session, ids), low_engagement_counts(session, ids)
        return [{**participant_public(p, a), "invalid_trials": invalid.get(p.id, 0),
                 "low_engagement_trials": low.get(p.id, 0)} for p, a in rows]


@router.post("/participants/{participant_id}/flags")
def set_flags(participant_id: PublicId, body: FlagsRequest, services: ServicesDep) -> dict[str, Any]:
    if body.excluded and not (body.reason or "").strip():
        raise ApiError(422, "reason_required", "excluding a participant needs a reason")
    with services.store.transaction() as session:
        row = participants.by_public_id(session, participant_id)
        if row is None:
            raise ApiError(404, "not_found", "no such participant")
        participants.set_flags(session, row.id, test_run=body.test_run, excluded=body.excluded, reason=body.reason)
        session.refresh(row)
        return participant_public(row, participants.assignment_of(session, row.id))


@router.post("/participants/{participant_id}/resume_link")
def resume_link(participant_id: PublicId, request: Request, services: ServicesDep) -> dict[str, Any]:
    """A one-time link that moves the participant to a new device (``server.admin.resume``): valid for
    ``resume_link_minutes``, void once used or once the participant's token changes."""
    expires = int(time.time()) + services.settings.resume_link_minutes * 60
    with services.store.transaction() as session:
        row = participants.by_public_id(session, participant_id)
        if row is None:
            raise ApiError(404, "not_found", "no such participant")
        code = make_code(link_secret(services.admin_token), row.public_id, row.token_hash, expires)
        session.add(EventRow(participant_id=row.id, trial_id=None, tick=None, kind="resume_link_made",
                             payload={"expires": expires}, created_at=utcnow()))
        path = resume_path(row.study_id, code)
    return {"participant_id": participant_id, "path": path, "url": str(request.base_url).rstrip("/") + path,
            "expires_at": datetime.fromtimestamp(expires, UTC).isoformat()}


@router.get("/participants/{participant_id}/answers")
def answers(participant_id: PublicId, services: ServicesDep) -> dict[str, Any]:
    with services.store.transaction() as session:
        row = participants.by_public_id(session, participant_id)
        if row is None:
            raise ApiError(404, "not_found", "no such participant")
        return participant_answers(session, row, services.catalog.get(row.study_id))


def _recruit_ids(services: Services, participant_ids: set[int]) -> dict[int, str | None]:
    with services.store.transaction() as session:
        return {pid: recruit for pid, (_, recruit) in participant_names(session, participant_ids).items()}


def _live_since(services: Services) -> datetime:
    """Running trials active since then count as live in another process (``server.admin.stored_live``)."""
    return utcnow() - timedelta(seconds=2 * services.settings.sweep_interval_s + 5)


@router.get("/live")
async def live(services: ServicesDep) -> list[dict[str, Any]]:
    """The live trials of every server process: this one's from memory, each taken on the event loop between two of
    its steps (:func:`live_trial`), the others' from the store."""
    here = process_name()
    mine = [{**g.meta.to_dict(), "tick": g.engine.tick, **g.status(), "process": here, "source": "process"}
            for g in services.registry.live()]
    recruit, elsewhere = await asyncio.to_thread(_live_from_store, services, {t["participant_id"] for t in mine})
    out = [{**t, "recruit_id": recruit.get(t["participant_id"])} for t in mine] + elsewhere
    return sorted(out, key=lambda t: t["trial_id"])


def _live_from_store(services: Services, participant_ids: set[int]) -> tuple[dict[int, str | None],
                                                                          list[dict[str, Any]]]:
    """The recruiting ids of this process's live participants, and the trials other processes run."""
    recruit = _recruit_ids(services, participant_ids)
    elsewhere: list[dict[str, Any]] = []
    with services.store.transaction() as session:
        for row in running_elsewhere(session, services.catalog.studies, set(services.registry.games),
                                     _live_since(services)):
            entry = stored_summary(session, row, services.catalog)
            if entry is not None:
                elsewhere.append(entry)
    return recruit, elsewhere


def _stored_live(services: Services, trial_id: int) -> dict[str, Any] | None:
    with services.store.transaction() as session:
        return stored_live_view(session, services.catalog, trial_id)


@router.get("/live/{trial_id}")
async def live_trial(trial_id: TrialId, services: ServicesDep) -> dict[str, Any]:
    """The spectator view of a running trial, whichever process runs it (another's lags by ≤ one flush). A trial of
    this process is viewed on the event loop, between two of its steps, so that every part of the view (its tick,
    frame, KB and field of view) is of the same step; the store is read off the loop."""
    game = services.registry.games.get(trial_id)
    if game is None:
        stored = await asyncio.to_thread(_stored_live, services, trial_id)
        if stored is None:
            raise ApiError(404, "not_live", "no running trial with this id")
        return stored
    view = live_view(game)
    recruit = await asyncio.to_thread(_recruit_ids, services, {game.meta.participant_id})
    view["trial"]["recruit_id"] = recruit.get(game.meta.participant_id)
    return view


@router.get("/trials")
def list_trials(services: ServicesDep, study_id: Annotated[str | None, Query(max_length=64)] = None,
                participant_id: Annotated[str | None, Query(max_length=64)] = None) -> list[dict[str, Any]]:
    with services.store.transaction() as session:
        pid = None
        if participant_id is not None:
            row = participants.by_public_id(session, participant_id)
            if row is None:
                return []
            pid = row.id
        rows = trials.list_trials(session, participant_id=pid, study_id=study_id)
        names = participant_names(session, {r.participant_id for r in rows})
        return [trial_public(r, *names.get(r.participant_id, (None, None))) for r in rows]


@router.get("/trials/{trial_id}")
def trial_replay(trial_id: TrialId, services: ServicesDep, start: TickStart = 0,
                 limit: Annotated[int, Query(ge=1, le=10_000)] = 10_000) -> dict[str, Any]:
    """A stored trial for replay: its row, the kitchen grid, the initial state and the ticks from ``start``."""
    with services.store.transaction() as session:
        row = session.get(TrialRow, trial_id)
        if row is None:
            raise ApiError(404, "not_found", "no such trial")
        names = participant_names(session, {row.participant_id})
        ticks = trials.ticks(session, trial_id, start, limit)
        loaded = services.catalog.get(row.study_id)
        layout = loaded.layouts.get(row.kitchen) if loaded else None
        return {
            "trial": trial_public(row, *names.get(row.participant_id, (None, None))),
            "layout": {"name": row.kitchen, "rows": layout.text().splitlines()} if layout else None,
            "initial_state": row.initial_state,
            "ticks": [{c.name: getattr(t, c.name) for c in t.__table__.columns if c.name != "trial_id"}
                      for t in ticks],
        }


@router.get("/trials/{trial_id}/frames")
def trial_frames(trial_id: TrialId, services: ServicesDep, start: TickStart = 0,
                 limit: Annotated[int, Query(ge=1, le=5_000)] = 2_000) -> dict[str, Any]:
    """A stored trial drawn tick by tick for the replay viewer (see ``server.admin.replay``)."""
    with services.store.transaction() as session:
        row = session.get(TrialRow, trial_id)
        if row is None:
            raise ApiError(404, "not_found", "no such trial")
        names = participant_names(session, {row.participant_id})
        stored = trials.ticks(session, trial_id, max(start, 1), limit)
        frames = replay(services.catalog.get(row.study_id), row, stored, start=start, limit=limit)
        return {"trial": trial_public(row, *names.get(row.participant_id, (None, None))), **frames}


@router.get("/trials/{trial_id}/events")
def trial_events(trial_id: TrialId, services: ServicesDep) -> list[dict[str, Any]]:
    with services.store.transaction() as session:
        return [{"id": e.id, "tick": e.tick, "kind": e.kind, "payload": e.payload,
                 "created_at": e.created_at.isoformat()} for e in trials.events(session, trial_id)]


@router.get("/robots")
def robots(services: ServicesDep) -> dict[str, Any]:
    return services.pool.describe()
