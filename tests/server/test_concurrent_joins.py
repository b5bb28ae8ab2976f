"""200 simultaneous joins, spread over two server processes sharing one database, stay balanced
(max − min ≤ 1 over the condition orders) and nobody is assigned twice — on SQLite and PostgreSQL. 20 of the
recruiting ids join twice at once from browsers without a token: one join wins, the other is refused."""

from __future__ import annotations

import asyncio
from collections import Counter
from typing import Any

import httpx
import pytest
from sqlalchemy import func, select
from steakhouse_testing import ProcessServer

from store.engine import Store
from store.tables import AssignmentRow, ParticipantRow
from study_config import STUDY_DIR

pytestmark = pytest.mark.slow
JOINS = 200
REPEATS = 20


async def join_all(urls: list[str]) -> list[dict[str, Any]]:
    limits = httpx.Limits(max_connections=JOINS + REPEATS, max_keepalive_connections=0)
    async with httpx.AsyncClient(timeout=120, limits=limits) as client:
        async def join(i: int) -> dict[str, Any]:
            pid = f"P{i % JOINS:04d}"
            response = await client.post(f"{urls[i % len(urls)]}/api/studies/paper_study/join",
                                         json={"recruiting": {"PROLIFIC_PID": pid, "STUDY_ID": "s"}})
            if response.status_code == 409:
                return {"refused": response.json()["detail"]["code"], "pid": pid}
            response.raise_for_status()
            return {**response.json(), "pid": pid}

        return list(await asyncio.gather(*(join(i) for i in range(JOINS + REPEATS))))


def test_two_hundred_simultaneous_joins_stay_balanced(db_url, tmp_path, many_connections):
    study = STUDY_DIR / "paper_study.yaml"
    servers = []
    try:
        for i in range(2):
            servers.append(ProcessServer(study=study, database_url=db_url, workers=0,
                                         log=tmp_path / f"server{i}.log").launch())
        for server in servers:
            server.wait_ready()
        answers = asyncio.run(join_all([s.url for s in servers]))
    finally:
        for server in servers:
            server.kill()
    by_pid: dict[str, set[str]] = {}
    for answer in answers:
        if "participant_id" in answer:
            by_pid.setdefault(answer["pid"], set()).add(answer["participant_id"])
    assert len(by_pid) == JOINS and all(len(ids) == 1 for ids in by_pid.values()), "one participant per id"
    assert [a["refused"] for a in answers if "refused" in a] == ["already_started"] * REPEATS
    store = Store(db_url)
    try:
        with store.transaction() as session:
            orders = Counter(session.scalars(select(AssignmentRow.order_index)))
            participants = session.scalar(select(func.count()).select_from(ParticipantRow))
            assigned = session.scalar(select(func.count(func.distinct(AssignmentRow.participant_id))))
    finally:
        store.dispose()
    assert participants == assigned == sum(orders.values()) == JOINS
    assert len(orders) == 4
    assert max(orders.values()) - min(orders.values()) <= 1, orders
