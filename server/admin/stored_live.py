"""The live view of a trial that another server process runs, read from the store (docs/operations.md §4).

A live trial's world, robot planner and websocket live in the memory of one process. To let the admin of
*any* process watch it, we chose **snapshots in the store**, and the snapshots already exist: every process
stores each tick of each trial — world, the participant's modelled KB and controller, the robot's decision —
at least every flush interval (``STEAKHOUSE_FLUSH_INTERVAL_S``, 0.5 s). The spectator view is rebuilt from
the trial's last stored tick with the same functions the owning process uses (``server.game.restore``,
``server.game.snapshot``, ``server.admin.scenes``). Why this and not the alternatives:

- it adds no work to the game loop (no extra writes: the capacity budget of docs/operations.md §2 stays the
  game's), needs no process to know another's address, and works on PostgreSQL and on SQLite alike;
- it keeps working when the owning process dies: the view shows the last stored tick until a survivor
  resumes the trial;
- the price is a lag of at most one flush interval (``as_of`` is when the shown tick was stored).
  PostgreSQL ``LISTEN``/``NOTIFY`` would need a listening connection per process, payloads under 8 kB and
  PostgreSQL only; forwarding to the owning process would need every process's internal address and fail
  with that process.

A running trial counts as live elsewhere while the store saw it active (a flushed tick, a connection event,
the owner's sweep) within ``window``.
"""

from __future__ import annotations

from collections.abc import Iterable
from datetime import datetime
from typing import Any

from sqlalchemy import func, select
from sqlalchemy.orm import Session

from server.admin.live import scene_view
from server.game import snapshot
from server.game.health import RobotHealth
from server.game.restore import trial_engine, trial_meta
from store import trials
from store.tables import EventRow, ParticipantRow, TickRow, TrialRow
from study_config.catalog import Catalog

LATENESS_TICKS = 5000
"""Ticks over which the lateness percentiles are taken (as ``LiveGame.lateness`` keeps)."""


def running_elsewhere(session: Session, study_ids: Iterable[str], local: set[int], since: datetime) -> list[TrialRow]:
    """Running trials of ``study_ids`` active since ``since`` that this process does not run."""
    rows = session.scalars(select(TrialRow).where(TrialRow.status == trials.RUNNING,
                                                  TrialRow.study_id.in_(list(study_ids)),
                                                  TrialRow.last_active_at >= since).order_by(TrialRow.id))
    return [row for row in rows if row.id not in local]


def _extras(session: Session, row: TrialRow, catalog: Catalog) -> dict[str, Any]:
    """What the owning process keeps in memory, as far as the store has it."""
    def last_event(*kinds: str) -> EventRow | None:
        return session.scalar(select(EventRow).where(EventRow.trial_id == row.id, EventRow.kind.in_(kinds))
                              .order_by(EventRow.id.desc()).limit(1))

    link, start = last_event("connect", "disconnect"), last_event("trial_start", "resume")
    counts: dict[str, int] = dict(session.execute(
        select(EventRow.kind, func.count()).where(EventRow.trial_id == row.id,
                                                  EventRow.kind.in_(("deadline_miss", "stall_hint")))
        .group_by(EventRow.kind)).all())
    misses, hints = counts.get("deadline_miss", 0), counts.get("stall_hint", 0)
    lateness = list(session.scalars(select(TickRow.lateness_ms).where(TickRow.trial_id == row.id)
                                    .order_by(TickRow.tick.desc()).limit(LATENESS_TICKS)))[::-1]
    loaded = catalog.get(row.study_id)
    timing = loaded.study.timing if loaded is not None else None
    decisions, missed = trials.decision_counts(session, row.id)
    health = (RobotHealth(loaded.study.validity.max_missed_decisions_pct, loaded.rules.horizon, decisions, missed,
                          row.invalid_reason).to_dict() if loaded is not None else None)
    return {"connected": link is not None and link.kind == "connect", "deadline_misses": misses,
            "stall_hints": hints, "health": health,
            "lateness_ms": snapshot.percentiles(lateness), "mode": timing.mode if timing else None,
            "tick_rate_hz": timing.tick_rate_hz if timing else None,
            "process": start.payload.get("process") if start is not None else None, "source": "store"}


def stored_summary(session: Session, row: TrialRow, catalog: Catalog) -> dict[str, Any] | None:
    """One entry of ``/api/admin/live`` for a trial another process runs (the fields of a local entry)."""
    loaded, participant = catalog.get(row.study_id), session.get(ParticipantRow, row.participant_id)
    if loaded is None or participant is None:
        return None
    extras = _extras(session, row, catalog)
    return {**trial_meta(loaded, participant, row).to_dict(), "recruit_id": participant.recruit_id,
            "tick": row.ticks, **{k: extras[k] for k in ("connected", "deadline_misses", "stall_hints", "health",
                                                         "lateness_ms", "process", "source")}}


def stored_live_view(session: Session, catalog: Catalog, trial_id: int) -> dict[str, Any] | None:
    """The spectator view and scene of running trial ``trial_id`` at its last stored tick; ``None`` when it
    is not running or its study is not served here."""
    row = session.get(TrialRow, trial_id)
    if row is None or row.status != trials.RUNNING:
        return None
    loaded, participant = catalog.get(row.study_id), session.get(ParticipantRow, row.participant_id)
    if loaded is None or participant is None:
        return None
    last = trials.last_tick(session, row.id)
    engine = trial_engine(loaded, row, last)
    extras = _extras(session, row, catalog)
    spectator = snapshot.spectator(trial_meta(loaded, participant, row), engine, {
        **extras, "decision": last.robot_info if last else None, "decision_ms": last.decision_ms if last else None,
        "as_of": (last.recorded_at if last else row.last_active_at).isoformat()})
    spectator["trial"]["recruit_id"] = participant.recruit_id
    return scene_view(spectator, engine)
