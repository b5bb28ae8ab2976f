"""Admission control: this server process never runs more live trials than it can hold on time
(docs/operations.md, "Admission control").

A trial needs a **slot** before it starts (or resumes from the store). There are ``capacity`` slots; a
participant who reaches a round while all are taken gets a :class:`Ticket` in a first-come, first-served
line (a trial being resumed goes ahead of new ones: it was already admitted once). Freeing a slot hands it
to the first ticket at once. Waiting is bounded by the caller (``max_wait_s``): past it the participant is
turned away, never given a robot that cannot keep up.

The expected wait shown to a participant is ``ceil(position / capacity) × mean slot time``, where the mean
slot time is the mean of the last :data:`HISTORY` trials' slot times in this process (the study's trial
length, horizon ÷ tick rate, until there are any).

Slots are per process: several server processes each admit up to their own capacity (docs/operations.md,
"Admission control").
State lives in one object made at start-up and is touched from the event loop's thread only.
"""

from __future__ import annotations

import asyncio
import math
import os
import time
from collections import deque
from dataclasses import dataclass, field

HISTORY = 20
DEFAULT_MAX_WAIT_S = 600.0
"""How long a participant may wait for a slot before being screened out (``STEAKHOUSE_ADMISSION_MAX_WAIT_S``)."""
TRIAL_CORE_SHARE = 0.0205
"""CPU one live trial costs, as a share of one core: the server's and the robot workers' CPU over the trials
of ``benchmarks/load/capacity.py`` (docs/operations.md §2, measured 2026-12-02 05:37 UTC on the quiet 2-core
reference machine, FOV-aware robot at 5 Hz: N = 40, (30.9 % + 51.2 %) / 40 ≈ 2.05 % of a core; N = 60 cost
the same per trial)."""
SERVER_CORE_SHARE = 0.0077
"""The server process's part of it (30.9 % / 40): one process runs its game loops on one core, whatever the
machine has."""
USABLE_CORE_SHARE = 0.4105
"""Share of a core that live trials may use with no trial invalid: what N = 40 used on the reference machine
(82.1 % of 200 %). At twice a cap of 40 (80 seats, 30 s trials) no trial of 205 passed the invalid-trial
threshold; at twice a cap of 60, 13 of 298 did (trials start and end all the time there, and each start's
first decisions are its costliest), although 60 long trials at once passed ``capacity.py``."""


def default_capacity(cpu_count: int | None = None) -> int:
    """``floor(cores × USABLE_CORE_SHARE / TRIAL_CORE_SHARE)``, but no more than one core's worth of game loops
    (``USABLE_CORE_SHARE / SERVER_CORE_SHARE``); at least 1. 40 on 2 cores, 20 on 1, 53 from 3 cores up."""
    cores = cpu_count if cpu_count is not None else (os.cpu_count() or 1)
    machine = math.floor(cores * USABLE_CORE_SHARE / TRIAL_CORE_SHARE + 1e-9)
    one_loop = math.floor(USABLE_CORE_SHARE / SERVER_CORE_SHARE + 1e-9)
    return max(1, min(machine, one_loop))


@dataclass(eq=False)
class Ticket:
    """One participant's place in line; ``granted`` is set when they get a slot."""

    key: int
    since: float
    granted: asyncio.Event = field(default_factory=asyncio.Event)
    changed: asyncio.Event = field(default_factory=asyncio.Event)
    """Set whenever the line moves (the waiter re-reads its position and clears it)."""


class Admission:
    def __init__(self, capacity: int) -> None:
        if capacity < 1:
            raise ValueError("the live-trial capacity must be at least 1")
        self.capacity = capacity
        self._held: dict[int, float] = {}
        self._line: deque[Ticket] = deque()
        self._slot_times: deque[float] = deque(maxlen=HISTORY)

    @property
    def live(self) -> int:
        return len(self._held)

    @property
    def waiting(self) -> int:
        return len(self._line)

    def holds(self, key: int) -> bool:
        return key in self._held

    def try_enter(self, key: int) -> bool:
        """Take a slot for ``key`` now if one is free and nobody waits (``True`` when ``key`` holds one)."""
        if key in self._held:
            return True
        if len(self._held) < self.capacity and not self._line:
            self._held[key] = time.monotonic()
            return True
        return False

    def enqueue(self, key: int, *, first: bool = False) -> Ticket:
        """A place in line for ``key`` (at the front when ``first``); granted at once if a slot is free."""
        ticket = Ticket(key, time.monotonic())
        if first:
            self._line.appendleft(ticket)
        else:
            self._line.append(ticket)
        self._grant()
        self._moved()
        return ticket

    def position(self, ticket: Ticket) -> int:
        """1 for the first in line; 0 once granted (or no longer waiting)."""
        for number, waiting in enumerate(self._line, start=1):
            if waiting is ticket:
                return number
        return 0

    def eta_s(self, position: int, default_slot_s: float) -> float:
        """Expected wait of the ``position``-th in line, in seconds (see the module docstring)."""
        mean = sum(self._slot_times) / len(self._slot_times) if self._slot_times else default_slot_s
        return math.ceil(position / self.capacity) * mean

    def leave(self, ticket: Ticket) -> None:
        """Give up a place in line (timed out, or the participant left); a granted slot is released."""
        if ticket in self._line:
            self._line.remove(ticket)
            self._moved()
        elif ticket.granted.is_set():
            self.release(ticket.key)

    def release(self, key: int) -> None:
        """Free ``key``'s slot (its trial ended or was unloaded) and hand it to the first in line."""
        since = self._held.pop(key, None)
        if since is None:
            return
        self._slot_times.append(time.monotonic() - since)
        self._grant()
        self._moved()

    def _grant(self) -> None:
        while self._line and len(self._held) < self.capacity:
            ticket = self._line.popleft()
            self._held[ticket.key] = time.monotonic()
            ticket.granted.set()

    def _moved(self) -> None:
        for ticket in self._line:
            ticket.changed.set()
