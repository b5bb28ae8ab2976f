"""Run N simulated participants against a server, at most ``jobs`` at a time, each with its own seeded
generator (``numpy.random.default_rng([seed, index, trial])`` per trial; ``pilot.client.trial_rng``): the same seed
gives the same participants' choices (the server's trial seeds come from the store, and thread timing can still reorder
joins)."""

from __future__ import annotations

import asyncio
from collections.abc import Sequence
from dataclasses import dataclass, field

import httpx

from pilot.client import Outcome, Seat, SimulatedParticipant, tls_context
from pilot.progress import Progress


@dataclass
class PilotResult:
    outcomes: list[Outcome] = field(default_factory=list)
    failures: list[str] = field(default_factory=list)
    seconds: float = 0.0
    invalid_trials: int | None = None
    """Trials of these participants the server marked invalid (robot decisions past their deadline); ``None`` when
    the server could not be asked."""
    low_engagement_trials: int | None = None
    """Trials of these participants the server marked low-engagement (played without them taking part)."""


async def trial_health(seat: Seat, outcomes: Sequence[Outcome]) -> tuple[int, int] | None:
    """``(invalid, low-engagement)`` trials of the participants of ``outcomes``, as the server's admin list of
    participants counts them; ``None`` when it cannot be read."""
    ids = {o.participant_id for o in outcomes if o.participant_id}
    try:
        async with httpx.AsyncClient(base_url=seat.base_url, timeout=60, verify=tls_context()) as http:
            response = await http.get("/api/admin/participants", params={"study_id": seat.loaded.id},
                                      headers={"Authorization": f"Bearer {seat.admin_token}"})
    except httpx.HTTPError:
        return None
    if response.status_code >= 400:
        return None
    mine = [row for row in response.json() if row.get("participant_id") in ids]
    return (sum(int(row.get("invalid_trials", 0)) for row in mine),
            sum(int(row.get("low_engagement_trials", 0)) for row in mine))


async def run_pilot(seat: Seat, participants: int, jobs: int, seed: int, progress: Progress | None = None,
                    names: Sequence[str] | None = None) -> PilotResult:
    result = PilotResult()
    gate = asyncio.Semaphore(max(jobs, 1))
    loop = asyncio.get_running_loop()
    started = loop.time()
    names = list(names) if names is not None else [f"pilot-{seed}-{i + 1}" for i in range(participants)]

    async def one(index: int) -> None:
        async with gate:
            who = SimulatedParticipant(seat, names[index], (seed, index),
                                       progress.rounds if progress else lambda d: None)
            try:
                result.outcomes.append(await who.run())
                if progress:
                    progress.finished(names[index], True)
            except Exception as exc:
                note = f"{type(exc).__name__}: {str(exc)[:300]}"
                result.failures.append(f"{names[index]}: {note}")
                if progress:
                    progress.finished(names[index], False, note)

    await asyncio.gather(*(one(i) for i in range(participants)))
    result.seconds = loop.time() - started
    health = await trial_health(seat, result.outcomes)
    if health is not None:
        result.invalid_trials, result.low_engagement_trials = health
    if progress:
        progress.close()
    return result
