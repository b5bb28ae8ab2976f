"""One owner per live round across server processes, behind the project's nginx (``server/deploy/nginx.conf``) on
PostgreSQL: a participant's connection moves to the other process mid-round, and the round is run by one process
at a time (docs/deploy.md, "One owner per round"; the lease: ``store/lease.py``).

Four ways a connection moves, each while other participants play on both processes:

- **resume link, old socket closed**: the participant leaves, the experimenter's resume link gives them a new token
  whose websocket the proxy hashes to the other process (links are made until one does);
- **resume link, old socket open**: the same while the old browser still plays; it is told ``moved``;
- **plain reconnect, old socket closed**: the proxy's websocket upstream loses the round's process (an operator's
  change, a process marked down) and the same token reconnects to the other one; when the process is back, the
  next reconnect moves the round back there;
- **plain reconnect, old socket open**: a second connection with the same token reaches the other process while
  the first still plays through nginx's old worker; the first is told ``replaced``.

Then every round is played to its end. Checked from the store and the processes' logs: each round finished once
(one ``trial_end``, none ``abandoned``), every tick stored once (1..n), every stored tick carries the epoch of the
process that stepped it, epochs never go back along a round's ticks and each belongs to one process (one owner at
any tick), no tick row clashed (no constraint violation logged), every moved participant completed the study.
``-s`` prints the drill's numbers (docs/operations.md §4.2).
"""

from __future__ import annotations

import asyncio
import contextlib
import re
import time
from collections import Counter
from dataclasses import dataclass, field
from typing import Any

import pytest
from nginx_proxy import ProxiedPlayer
from sqlalchemy import select
from steakhouse_testing import ProcessServer, Socket, eventually, play_to_end
from websockets.exceptions import ConnectionClosed

from store.engine import Store
from store.tables import EventRow, TickRow, TrialRow

pytestmark = [pytest.mark.slow, pytest.mark.postgres]
ADMIN = {"Authorization": "Bearer admin-secret"}
SEATS = 8
RATE = 10


@dataclass
class Seat:
    player: ProxiedPlayer
    sock: Socket | None = None
    trial_id: int = 0
    process: str = ""
    """The pid of the process that runs the round now."""
    told: list[str] = field(default_factory=list)
    """What the round's old sockets were told when the round moved (``moved`` / ``replaced``)."""
    end: dict[str, Any] | None = None
    opened: list[Socket] = field(default_factory=list)
    """Every socket opened, closed at the end (the server closes the old ones; the client side is closed here)."""

    async def close(self) -> None:
        for sock in self.opened:
            with contextlib.suppress(Exception):
                await sock.close()
        await self.player.close()


def store_rows(db_url: str) -> dict[str, Any]:
    store = Store(db_url)
    try:
        with store.transaction() as session:
            ticks = [(t, n, e) for t, n, e in session.execute(
                select(TickRow.trial_id, TickRow.tick, TickRow.epoch).order_by(TickRow.trial_id, TickRow.tick))]
            events = [(e.trial_id, e.kind, e.epoch, e.payload) for e in
                      session.scalars(select(EventRow).where(EventRow.trial_id.is_not(None)).order_by(EventRow.id))]
            rounds = {r.id: (r.status, r.attempt, r.ticks, r.lease_epoch) for r in session.scalars(select(TrialRow))}
            return {"ticks": ticks, "events": events, "rounds": rounds}
    finally:
        store.dispose()


def owners(events: list[tuple[Any, ...]]) -> dict[int, dict[int, str]]:
    """Trial → epoch → the pid of the process that started or took over the round under it."""
    out: dict[int, dict[int, str]] = {}
    for trial_id, kind, epoch, payload in events:
        if kind in ("trial_start", "resume"):
            out.setdefault(trial_id, {})[epoch] = str(payload["process"]).rsplit(":", 1)[1]
    return out


async def connect_epochs(db_url: str, trial_id: int, count: int) -> list[int]:
    """The epochs of the round's ``connect`` events, once there are ``count`` of them (stored within a flush)."""
    def read() -> list[int]:
        return [e for t, kind, e, _ in store_rows(db_url)["events"] if t == trial_id and kind == "connect"]

    found: list[int] = await asyncio.to_thread(eventually, read, lambda got: len(got) >= count, 30.0)
    assert len(found) >= count, f"trial {trial_id}: {found}"
    return found


async def read_until_told(sock: Socket) -> str:
    """Read an open socket (the world steps on: fixed rate) until the server tells it to go; the error code."""
    while True:
        try:
            message = await sock.recv(timeout=30)
        except ConnectionClosed:
            return "closed"
        if message["type"] == "error" and message["code"] in ("moved", "replaced"):
            with contextlib.suppress(ConnectionClosed, TimeoutError):
                await sock.recv(timeout=5)  # the close that follows
            return str(message["code"])


async def open_round(seat: Seat) -> dict[str, Any]:
    sock: Socket = await seat.player.socket()
    hello: dict[str, Any] = await sock.recv()
    assert hello["type"] == "hello", hello
    seat.sock, seat.trial_id = sock, hello["trial"]["id"]
    seat.opened.append(sock)
    return hello


async def resume_link(seat: Seat) -> None:
    """The experimenter's resume link, redeemed by the participant's new browser (a new token)."""
    participant = (await seat.player.session())["participant_id"]
    made = await seat.player.http.post(f"/api/admin/participants/{participant}/resume_link", headers=ADMIN)
    made.raise_for_status()
    code = made.json()["path"].split("#resume=", 1)[1]
    redeemed = await seat.player.http.post("/api/studies/tiny/resume", json={"code": code})
    redeemed.raise_for_status()
    seat.player.token = redeemed.json()["token"]


async def move_by_resume_link(seat: Seat, db_url: str, keep_old_open: bool) -> int:
    """Resume links until the new token's websocket reaches the other process (the proxy hashes tokens); the
    number of links used. With ``keep_old_open`` the old socket stays open and reading; an attempt that reaches the
    same process replaces it there (as a second window does), and the new socket becomes the old one."""
    old = seat.sock
    assert old is not None
    watching = asyncio.create_task(read_until_told(old)) if keep_old_open else None
    if not keep_old_open:
        await old.close()
    start_epoch = (await connect_epochs(db_url, seat.trial_id, 1))[-1]
    for attempt in range(1, 16):
        await resume_link(seat)
        connects = len(await connect_epochs(db_url, seat.trial_id, 1))
        await open_round(seat)
        epochs = await connect_epochs(db_url, seat.trial_id, connects + 1)
        if epochs[-1] != start_epoch:  # taken over by the other process
            if watching is not None:
                seat.told.append(await asyncio.wait_for(watching, 30))
            return attempt
        assert seat.sock is not None
        if watching is not None:  # reached the same process: the new socket replaced the old one there
            assert await asyncio.wait_for(watching, 30) == "replaced"
            watching = asyncio.create_task(read_until_told(seat.sock))
        else:
            await seat.sock.close()
    raise AssertionError("15 resume links all hashed to the same process")


@pytest.mark.parametrize("db_url", ["postgresql"], indirect=True)
def test_a_connection_moving_to_the_other_process_leaves_the_round_one_owner(db_url, study_file, tmp_path, nginx):
    study = study_file(timing={"tick_rate_hz": RATE}, world={"orders": 1, "horizon": 600, "kb_delay": 1})
    servers = [ProcessServer(study=study, database_url=db_url, workers=0, log=tmp_path / f"app{i}.log",
                             env={"STEAKHOUSE_FLUSH_INTERVAL_S": "0.5"}).launch() for i in range(2)]
    for server in servers:
        server.wait_ready()
    pids = {str(s.process.pid) for s in servers if s.process is not None}
    addresses = {str(s.process.pid): f"127.0.0.1:{s.port}" for s in servers if s.process is not None}
    try:
        proxy = nginx(list(addresses.values()))

        async def drill() -> tuple[list[Seat], dict[str, Any]]:
            seats = [Seat(ProxiedPlayer(proxy.url)) for _ in range(SEATS)]
            try:
                return await moves(seats)
            finally:
                for seat in seats:
                    await seat.close()

        async def moves(seats: list[Seat]) -> tuple[list[Seat], dict[str, Any]]:
            for i, seat in enumerate(seats):
                await seat.player.ready(PROLIFIC_PID=f"owner-{i}")
                await open_round(seat)
            started = await asyncio.to_thread(eventually, lambda: owners(store_rows(db_url)["events"]),
                                              lambda o: all(s.trial_id in o for s in seats))
            for seat in seats:
                seat.process = started[seat.trial_id][min(started[seat.trial_id])]
            # The process answering REST through the proxy (hashed on the client address): a round it runs is
            # listed from its memory, the others' from the store.
            live = (await seats[0].player.http.get("/api/admin/live", headers=ADMIN)).json()
            rest = {t["trial_id"] for t in live if t["source"] == "process"}
            on_other = [s for s in seats if s.trial_id not in rest]
            assert on_other, "all rounds on the process that answers REST: rerun (1 in 2^8)"
            by_process = Counter(s.process for s in seats)
            busiest = by_process.most_common(1)[0][0]
            b = on_other[0]  # resume link with the old socket open: the redeem must not reach the round's process
            c, d = [s for s in seats if s.process == busiest and s is not b][:2]
            a = next(s for s in seats if s not in (b, c, d))
            numbers: dict[str, Any] = {}
            numbers["links_a"] = await move_by_resume_link(a, db_url, keep_old_open=False)
            numbers["links_b"] = await move_by_resume_link(b, db_url, keep_old_open=True)
            # Plain reconnects: the proxy's websocket upstream loses the busiest process.
            other = next(p for p in pids if p != busiest)
            await asyncio.to_thread(proxy.reload, [addresses[other]])
            assert c.sock is not None and d.sock is not None
            await c.sock.close()
            connects_c = len(await connect_epochs(db_url, c.trial_id, 1))
            await open_round(c)
            moved_c = await connect_epochs(db_url, c.trial_id, connects_c + 1)
            old_d = d.sock
            watching = asyncio.create_task(read_until_told(old_d))
            connects_d = len(await connect_epochs(db_url, d.trial_id, 1))
            await open_round(d)
            moved_d = await connect_epochs(db_url, d.trial_id, connects_d + 1)
            d.told.append(await asyncio.wait_for(watching, 30))
            # The process is back in the upstream: C's next reconnect is hashed to it again, and it takes the round
            # back (its own copy was dropped when it lost the lease).
            await asyncio.to_thread(proxy.reload, None)
            assert c.sock is not None
            await c.sock.close()
            await open_round(c)
            back_c = await connect_epochs(db_url, c.trial_id, connects_c + 2)
            numbers["epochs_c"], numbers["epochs_d"] = back_c, moved_d
            assert moved_c[-1] > moved_c[-2] and back_c[-1] > back_c[-2] and moved_d[-1] > moved_d[-2]

            async def finish(seat: Seat) -> None:
                assert seat.sock is not None
                seat.end = await play_to_end(seat.sock, timeout=120)
                await seat.sock.close()
                session = await seat.player.session()
                if session["state"] == "questionnaire":
                    (await seat.player.post("/api/session/questionnaire",
                                            {"questionnaire_id": "q", "answers": {"a": 3}})).raise_for_status()
                    session = await seat.player.session()
                assert session["state"] == "done", session["state"]

            await asyncio.gather(*(finish(s) for s in seats))
            numbers["moved"] = [seats.index(s) for s in (a, b, c, d)]
            return seats, numbers

        began = time.monotonic()
        seats, numbers = asyncio.run(drill())
        seconds = time.monotonic() - began
    finally:
        for server in servers:
            server.stop()
    stored = store_rows(db_url)
    logs = {pid: (tmp_path / f"app{i}.log").read_text(errors="replace")
            for i, pid in enumerate(str(s.process.pid) for s in servers if s.process is not None)}
    by_trial: dict[int, list[tuple[int, int]]] = {}
    for trial_id, number, epoch in stored["ticks"]:
        by_trial.setdefault(trial_id, []).append((number, epoch))
    who = owners(stored["events"])
    ends = Counter((t, p["status"]) for t, kind, _, p in stored["events"] if kind == "trial_end")
    clashes = sum(text.count("violates a constraint") for text in logs.values())
    refused = sum(int(n) for text in logs.values() for n in re.findall(r"refused (\d+) row\(s\)", text))
    stopped = sum(text.count("another server process took the round over") for text in logs.values())
    takeovers = sum(1 for _, kind, _, _ in stored["events"] if kind == "resume")
    stepped_by: dict[tuple[int, int], set[str]] = {}
    for trial_id, number, epoch in stored["ticks"]:
        stepped_by.setdefault((trial_id, number), set()).add(who.get(trial_id, {}).get(epoch, "?"))
    owners_per_tick = Counter(len(processes) for processes in stepped_by.values())
    print(f"\nownership drill ({SEATS} rounds at {RATE} Hz, 2 processes behind nginx, PostgreSQL, {seconds:.1f} s): "
          f"rounds finished {sum(1 for r in stored['rounds'].values() if r[0] == 'finished')}, "
          f"ticks stored {len(stored['ticks'])}, takeovers {takeovers}, resume links used "
          f"{numbers['links_a']} + {numbers['links_b']}, rows refused from lost leases {refused}, "
          f"rounds stopped on losing their lease {stopped}, clashing tick rows {clashes}, "
          f"owners per tick {dict(owners_per_tick)}, trial_end events {dict(Counter(s for _, s in ends))}, "
          f"old sockets told {[s.told for s in seats if s.told]}")
    assert clashes == 0, "no tick row clashed"
    assert len(stored["rounds"]) == SEATS
    for seat in seats:
        status, attempt, ticks, _ = stored["rounds"][seat.trial_id]
        assert seat.end is not None and seat.end["status"] == "finished" and seat.end["ticks"] == ticks
        assert (status, attempt) == ("finished", 1)
        assert ends[(seat.trial_id, "finished")] == 1 and ends[(seat.trial_id, "abandoned")] == 0
        stepped = by_trial[seat.trial_id]
        assert [n for n, _ in stepped] == list(range(1, ticks + 1)), "every tick stored once"
        epochs = [e for _, e in stepped]
        assert all(e is not None for e in epochs) and epochs == sorted(epochs), "one owner at a time, in order"
        assert set(epochs) <= set(who[seat.trial_id]), "every tick under an epoch a process took"
    moved = [seats[i] for i in numbers["moved"]]
    for seat in moved:
        processes = [who[seat.trial_id][e] for e in sorted(who[seat.trial_id])]
        assert len(processes) >= 2 and all(p in pids for p in processes), processes
        assert len(set(processes)) >= 2, "the round changed process"
    assert moved[1].told == ["moved"] and moved[3].told == ["replaced"], [s.told for s in moved]
    assert stopped >= 3, "the processes that lost a round with a copy in memory stopped it"
