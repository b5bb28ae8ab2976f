"""Two server processes on one PostgreSQL database, run directly (no proxy), as in the deployment of
``docs/operations.md``:

- joins spread over both processes stay balanced over the condition orders (max − min ≤ 1): assignment is
  one database transaction, whichever process runs it;
- the admin API of either process lists every participant and every stored trial of both;
- one live view: ``/api/admin/live`` of either process lists the live trials of both, and the spectator view
  of a trial the *other* process runs is rebuilt from the store (``server.admin.stored_live``): the same
  fields, at most a flush interval behind the owner's own view, and it moves on as the trial plays;
- a participant's websocket is pinned to the process running their trial (its world and robot planner are in
  that process's memory): coming back through the same process resumes the live trial.
"""

from __future__ import annotations

import asyncio
from collections import Counter
from typing import Any

import httpx
import pytest
from steakhouse_testing import Player, ProcessServer, eventually

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

        async def live_pair() -> dict[str, Any]:
            started = [await start_trial(url, f"live-{i}") for i, url in enumerate(urls)]
            # The other process's trial is listed from the store: its ticks and connection event arrive there
            # within a flush interval.
            views = tuple(eventually(lambda u=url: admin(u, "/api/admin/live"),
                                     lambda r: len(r[1]) == 2 and all(t["connected"] and t["tick"] >= 3 for t in r[1]))
                          for url in urls)
            # Process i watches the trial process 1 - i runs, then the owner's own view of it, then again.
            others = []
            for i, url in enumerate(urls):
                trial_id = started[1 - i][2]["trial"]["id"]
                first = admin(url, f"/api/admin/live/{trial_id}")
                own = admin(urls[1 - i], f"/api/admin/live/{trial_id}")
                later = eventually(lambda u=url, t=trial_id: admin(u, f"/api/admin/live/{t}"),
                                   lambda r, f=first: r[1]["tick"] > f[1]["tick"])
                others.append((first, own, later))
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
        assert status == 200 and [t["trial_id"] for t in live] == sorted(trial_ids), "one live list"
        sources = {t["trial_id"]: t["source"] for t in live}
        assert sources == {trial_ids[i]: "process", trial_ids[1 - i]: "store"}
        assert all(t["connected"] and t["tick"] >= 3 for t in live)
        (status, remote), (own_status, own), (_, later) = result["others"][i]
        assert status == own_status == 200 and remote["source"] == "store" and own["source"] == "process"
        assert remote["trial"] == own["trial"] and set(remote) == set(own) | {"as_of"}
        assert remote["process"] == own["process"] and remote["grid"] == own["grid"]
        assert 3 <= remote["tick"] <= own["tick"], "the stored view lags the owner's by at most a flush"
        assert remote["frame"]["tick"] == remote["tick"] and remote["connected"] is True
        assert later["tick"] > remote["tick"], "the view from the store follows the trial"
        status, stored = result["stored"][i]
        assert status == 200 and set(trial_ids) <= {t["trial_id"] for t in stored}
        status, studies = result["studies"][i]
        assert status == 200 and studies[0]["live_trials"] == 2
    assert result["resumed"]["trial"]["id"] == trial_ids[1] and result["resumed"]["resumed"] is True
