"""Two server processes on one PostgreSQL database, run directly (no proxy), as in the deployment of
``docs/operations.md``:

- joins spread over both processes stay balanced over the condition orders (max − min ≤ 1): assignment is
  one database transaction, whichever process runs it;
- the admin API of either process lists every participant and every stored trial of both;
- live trials are per process: ``/api/admin/live`` of a process lists the trials it runs (their world and
  robot planner are in its memory), which is why the proxy pins a participant's websocket to one process.
"""

from __future__ import annotations

import asyncio
from collections import Counter
from typing import Any

import httpx
import pytest
from steakhouse_testing import Player, ProcessServer

pytestmark = [pytest.mark.slow, pytest.mark.postgres]
JOINS = 60
ADMIN = {"Authorization": "Bearer admin-secret"}


async def join_all(urls: list[str]) -> list[dict[str, Any]]:
    async with httpx.AsyncClient(timeout=60) as client:
        async def join(i: int) -> dict[str, Any]:
            response = await client.post(f"{urls[i % 2]}/api/studies/tiny/join",
                                         json={"recruiting": {"PROLIFIC_PID": f"mp-{i}"}})
            response.raise_for_status()
            return {**response.json(), "process": i % 2}

        return list(await asyncio.gather(*(join(i) for i in range(JOINS))))


async def start_trial(url: str, pid: str) -> tuple[Player, Any, dict[str, Any]]:
    player = Player(url)
    await player.ready(PROLIFIC_PID=pid)
    sock = await player.socket()
    hello = await sock.recv()
    await sock.until(lambda m: m["type"] == "state" and m["tick"] >= 3)
    return player, sock, hello


def admin(url: str, path: str, **params: Any) -> Any:
    response = httpx.get(url + path, headers=ADMIN, params=params, timeout=30)
    return response.status_code, response.json()


@pytest.mark.parametrize("db_url", ["postgresql"], indirect=True)
def test_two_processes_share_assignment_and_admin_views(db_url, study_file, tmp_path):
    study = study_file(kitchens=["practice", "mid_2", "none_3"], factors=["kitchen"],
                       world={"orders": 1, "horizon": 3000, "kb_delay": 1})
    servers = [ProcessServer(study=study, database_url=db_url, workers=0, log=tmp_path / f"s{i}.log").launch()
               for i in range(2)]
    try:
        for server in servers:
            server.wait_ready()
        urls = [s.url for s in servers]
        joined = asyncio.run(join_all(urls))

        async def live_pair() -> tuple[dict[str, Any], ...]:
            started = [await start_trial(url, f"live-{i}") for i, url in enumerate(urls)]
            views = tuple(admin(url, "/api/admin/live") for url in urls)
            others = tuple(admin(url, f"/api/admin/live/{started[1 - i][2]['trial']['id']}")
                           for i, url in enumerate(urls))
            stored = tuple(admin(url, "/api/admin/trials", study_id="tiny") for url in urls)
            studies = tuple(admin(url, "/api/admin/studies") for url in urls)
            # The participant of process 1 comes back through the same process (as the proxy pins them).
            player, sock, hello = started[1]
            await sock.close()
            again = await player.socket()
            resumed = await again.recv()
            await again.close()
            for p, s, _ in started:
                await s.close()
                await p.close()
            return {"hellos": [h for _, _, h in started], "live": views, "others": others, "stored": stored,
                    "studies": studies, "first": hello, "resumed": resumed}

        result = asyncio.run(live_pair())
        participants = [admin(url, "/api/admin/participants", study_id="tiny") for url in urls]
    finally:
        for server in servers:
            server.kill()
    order_of = {p["participant_id"]: p["order_index"] for p in participants[0][1]}
    orders = Counter(order_of[j["participant_id"]] for j in joined)
    assert len(orders) == 6 and sum(orders.values()) == JOINS
    assert max(orders.values()) - min(orders.values()) <= 1, orders
    by_process = Counter(j["process"] for j in joined)
    assert by_process == {0: JOINS // 2, 1: JOINS // 2}
    everyone = {j["participant_id"] for j in joined}
    for status, listed in participants:
        assert status == 200
        assert everyone <= {p["participant_id"] for p in listed}, "each process lists both processes' joins"
    trial_ids = [h["trial"]["id"] for h in result["hellos"]]
    for i in range(2):
        status, live = result["live"][i]
        assert status == 200 and [t["trial_id"] for t in live] == [trial_ids[i]], "live trials are per process"
        assert result["others"][i][0] == 404 and result["others"][i][1]["detail"]["code"] == "not_live"
        status, stored = result["stored"][i]
        assert status == 200 and set(trial_ids) <= {t["trial_id"] for t in stored}
        status, studies = result["studies"][i]
        assert status == 200 and studies[0]["live_trials"] == 1
    assert result["resumed"]["trial"]["id"] == trial_ids[1] and result["resumed"]["resumed"] is True
