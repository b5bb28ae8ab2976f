"""Crash-aware time on the paper's clock (``wait_for_participant``): a server killed while the participant thinks
(the world waiting for them, no tick stored for seconds) and started again.

- Restarted within the grace window, and again after an outage longer than the window itself: the thinking
  participant's round resumes both times (the window counts time away while a server was up, and a server start
  restarts it), and they are not screened out.
- The round's wall-clock limit counts the connected time, thinking included, up to the crash (kept with the
  round's lease, ``trials.connected_s``), not only up to the last stored tick.
- The wait running at each crash is stored as a ``wait`` event when the round is taken again, so it enters the
  round's idle share.
"""

from __future__ import annotations

import asyncio
from typing import Any

import pytest
from sqlalchemy import select
from steakhouse_testing import Player, ProcessServer, Socket, eventually, play_to_end

from store import trials
from store.engine import Store
from store.tables import EventRow, TrialRow

pytestmark = pytest.mark.slow
GRACE_S = 6.0


def trial_row(db_url: str, trial_id: int) -> dict[str, Any]:
    store = Store(db_url)
    try:
        with store.transaction() as session:
            row = session.get(TrialRow, trial_id)
            assert row is not None
            ticks = trials.ticks(session, trial_id)
            waits = [e.payload for e in session.scalars(select(EventRow).where(
                EventRow.trial_id == trial_id, EventRow.kind == "wait"))]
            ends = [e.payload for e in session.scalars(select(EventRow).where(
                EventRow.trial_id == trial_id, EventRow.kind == "trial_end"))]
            return {"open_wait_s": row.open_wait_s, "connected_s": row.connected_s, "status": row.status,
                    "idle_pct": row.idle_pct, "ticks": [(t.tick, t.round_seconds) for t in ticks],
                    "waits": waits, "ends": ends}
    finally:
        store.dispose()


async def think(sock: Socket) -> int:
    """Choose a task, play it out, then choose nothing (the world waits): the tick the wait began at."""
    chosen_at: int | None = None
    while True:
        message = await sock.recv()
        if message["type"] != "state" or message["subtask"] is not None or not message["available"]:
            continue
        if chosen_at is None:
            chosen_at = int(message["tick"])
            await sock.send("select_subtask", subtask=message["available"][0])
        elif message["tick"] > chosen_at:
            return int(message["tick"])


def crash_while_thinking(server: ProcessServer, db_url: str, trial_id: int, seconds: float) -> dict[str, Any]:
    """Wait (on the store) until the round has waited ``seconds`` for the participant, then kill the server."""
    seen = eventually(lambda: trial_row(db_url, trial_id),
                      lambda row: (row["open_wait_s"] or 0.0) >= seconds, timeout=60)
    assert (seen["open_wait_s"] or 0.0) >= seconds, seen["open_wait_s"]
    server.kill()
    return trial_row(db_url, trial_id)


def test_a_thinking_participant_survives_a_crash_and_restart(db_url, study_file, tmp_path):
    study = study_file(timing={"mode": "wait_for_participant", "tick_rate_hz": 10, "max_round_seconds": 600,
                               "idle_nudge_seconds": 1000},
                       world={"orders": 1, "horizon": 300, "kb_delay": 1},
                       reconnect={"grace_seconds": GRACE_S, "after_grace": "abandon"})
    log = tmp_path / "server.log"
    servers: list[ProcessServer] = []

    def start() -> ProcessServer:
        servers.append(ProcessServer(study=study, database_url=db_url, workers=0, log=log).start())
        return servers[-1]

    async def on(server: ProcessServer, token: str) -> tuple[Player, Socket, dict[str, Any]]:
        """The participant's browser reconnecting with its token to (re)started ``server``."""
        player = Player(server.url)
        player.token = token
        sock = await player.socket()
        return player, sock, await sock.recv()

    async def scenario() -> dict[str, Any]:
        out: dict[str, Any] = {}
        server = await asyncio.to_thread(start)
        player = Player(server.url)
        await player.ready(PROLIFIC_PID="thinker")
        token = player.token
        sock = await player.socket()
        trial_id = out["trial_id"] = (await sock.recv())["trial"]["id"]
        out["waited_at"] = await think(sock)
        out["before"] = await asyncio.to_thread(crash_while_thinking, server, db_url, trial_id, 3.0)
        sock.ws.transport.abort()
        await player.close()
        # Restarted at once: within the grace window.
        server = await asyncio.to_thread(start)
        player, sock, out["hello_1"] = await on(server, token)
        out["resumed_at"] = await think(sock)
        out["second"] = await asyncio.to_thread(crash_while_thinking, server, db_url, trial_id, 2.0)
        sock.ws.transport.abort()
        await player.close()
        # An outage longer than the grace window itself: a server start restarts the count.
        await asyncio.sleep(GRACE_S + 1.0)
        server = await asyncio.to_thread(start)
        player, sock, out["hello_2"] = await on(server, token)
        out["end"] = await play_to_end(sock, timeout=120)
        await sock.close()
        out["session"] = await player.session()
        await player.close()
        return out

    try:
        out = asyncio.run(scenario())
    finally:
        for server in servers:
            server.kill()
    trial_id, before = out["trial_id"], out["before"]
    after = trial_row(db_url, trial_id)
    for hello in (out["hello_1"], out["hello_2"]):
        assert hello["type"] == "hello" and hello["resumed"] is True and hello["trial"]["id"] == trial_id, hello
    assert out["end"]["status"] == "finished" and after["status"] == "finished"
    assert [e["status"] for e in after["ends"]] == ["finished"], "one end, not abandoned"
    assert out["session"]["state"] in ("questionnaire", "done"), "not screened out"
    # The limit's count: the first tick stepped after the restart goes on from the connected time at the crash,
    # the thinking included, not from the last tick stored before it.
    last_tick_seconds = max(s or 0.0 for _, s in before["ticks"])
    assert (before["connected_s"] or 0.0) >= last_tick_seconds + 3.0
    resumed_from = [s for t, s in out["second"]["ticks"] if t > out["waited_at"]]
    assert out["resumed_at"] > out["waited_at"]
    assert resumed_from and (resumed_from[0] or 0.0) >= (before["connected_s"] or 0.0), resumed_from[:3]
    cut = [w["seconds"] for w in after["waits"] if w.get("cut_short")]
    assert len(cut) == 2 and cut[0] >= 3.0 and cut[1] >= 2.0, after["waits"]
    assert after["idle_pct"] is not None and after["idle_pct"] > 0
