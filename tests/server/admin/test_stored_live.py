"""The live view rebuilt from the store (``server.admin.stored_live``) is the view the owning process shows:
a trial paused at a known tick (its participant left) looks the same from memory and from its last stored
tick — world, field of view, modelled KB, scene, subtask and robot decision — on SQLite and PostgreSQL."""

from __future__ import annotations

import asyncio
from typing import Any

import httpx
import pytest
from steakhouse_testing import Player, eventually, play_until

from server.admin.stored_live import stored_live_view
from store import trials

ADMIN = {"Authorization": "Bearer admin-secret"}
APPROXIMATE = {"source", "as_of", "lateness_ms", "decision_ms"}


@pytest.mark.slow
def test_a_paused_trial_looks_the_same_from_memory_and_from_the_store(live_server, study_file):
    server = live_server([study_file(world={"orders": 1, "horizon": 300, "kb_delay": 1})])

    async def pause_inside_a_subtask() -> Any:
        """Play to tick 12 or later and leave while the cook has a subtask under way. The world runs on at
        30 Hz between the last state read and the close, so the subtask may end first: then come back (the
        paused trial resumes) and leave again, until the paused game holds a subtask."""
        player = Player(server.url)
        await player.ready(PROLIFIC_PID="watched")
        try:
            for _ in range(20):
                sock = await player.socket()
                hello = await sock.recv()
                trial_id = int(hello["trial"]["id"])
                state = await play_until(sock, 12)
                for _ in range(50):  # a subtask chosen on the last state read takes effect at a tick, and so is stored
                    if state["subtask"] is not None or not state["available"]:
                        break
                    state = await play_until(sock, state["tick"] + 1)
                await sock.close()
                game = await asyncio.to_thread(
                    eventually, lambda key=trial_id: services.registry.games.get(key),
                    lambda g: g is not None and g.connection is None)
                if game.connection is None and game.engine.controller.subtask is not None:
                    return game
        finally:
            await player.close()
        pytest.fail("the cook never left with a subtask under way")

    services = server.services
    game = asyncio.run(pause_inside_a_subtask())
    trial_id = game.meta.trial_id

    def stored_tick() -> int | None:
        with services.store.transaction() as session:
            last = trials.last_tick(session, trial_id)
            return last.tick if last else None

    def stored_view() -> dict[str, Any]:
        with services.store.transaction() as session:
            return stored_live_view(session, services.catalog, trial_id)  # type: ignore[return-value]

    assert eventually(stored_tick, lambda t: t == game.engine.tick) == game.engine.tick, "the paused tick is stored"
    # The disconnect event is written by the store's writer after the socket closed: wait until it is stored.
    stored = eventually(stored_view, lambda v: v is not None and v["connected"] is False)
    local = httpx.get(f"{server.url}/api/admin/live/{trial_id}", headers=ADMIN, timeout=10).json()
    assert local["source"] == "process" and stored["source"] == "store" and local["tick"] >= 12
    assert set(stored) == set(local) | {"as_of"}
    for key in set(local) - APPROXIMATE:
        assert stored[key] == local[key], key
    assert stored["lateness_ms"]["count"] == local["lateness_ms"]["count"] == local["tick"]
    assert stored["decision_ms"] == pytest.approx(local["decision_ms"], abs=1e-3)
    assert stored["subtask"] is not None


def test_a_trial_that_is_not_running_has_no_stored_live_view(live_server, study_file):
    server = live_server([study_file()])
    with server.services.store.transaction() as session:
        assert stored_live_view(session, server.services.catalog, 12345) is None
    response = httpx.get(f"{server.url}/api/admin/live/12345", headers=ADMIN, timeout=10)
    assert response.status_code == 404 and response.json()["detail"]["code"] == "not_live"
