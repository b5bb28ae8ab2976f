"""Run N simulated participants against a server, at most ``jobs`` at a time, each with its own seeded
generator (``numpy.random.default_rng([seed, index, trial])`` per trial; ``pilot.client.trial_rng``): the same seed
gives the same participants' choices (the server's trial seeds come from the store, and thread timing can still reorder
joins)."""

from __future__ import annotations

import asyncio
from collections.abc import Sequence
from dataclasses import dataclass, field

from pilot.client import Outcome, Seat, SimulatedParticipant
from pilot.progress import Progress


@dataclass
class PilotResult:
    outcomes: list[Outcome] = field(default_factory=list)
    failures: list[str] = field(default_factory=list)
    seconds: float = 0.0


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
    if progress:
        progress.close()
    return result
