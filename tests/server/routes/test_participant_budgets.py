"""Every participant-writable endpoint has a budget (``store/budget.py``): a flood of device reports, or of joins
with somebody's recruiting id, stores at most the budget's rows; the rest is counted on the latest stored row."""

from __future__ import annotations

import httpx
from sqlalchemy import select

from store.budget import DEVICE_REPORTS, REFUSED_JOINS
from store.tables import EventRow

LAPTOP = {"screen_width": 1440, "screen_height": 900, "viewport_width": 1280, "viewport_height": 720,
          "pixel_ratio": 2, "fine_pointer": True, "touch": False}
FLOOD = 100


def rows(server, kind: str) -> list[EventRow]:
    with server.services.store.transaction() as session:
        return list(session.scalars(select(EventRow).where(EventRow.kind == kind).order_by(EventRow.id)))


def test_a_device_report_flood_stores_at_most_the_budget(live_server, study_file):
    server = live_server([study_file()])
    with httpx.Client(base_url=server.url, timeout=30) as client:
        joined = client.post("/api/studies/tiny/join", json={"recruiting": {"PROLIFIC_PID": "flooder"}}).json()
        headers = {"Authorization": f"Bearer {joined['token']}"}
        answers = [client.post("/api/session/device", json={**LAPTOP, "viewport_width": 1000 + n}, headers=headers)
                   for n in range(FLOOD)]
        assert {a.status_code for a in answers} == {200}, "every report is answered"
        assert answers[-1].json()["device"]["ok"] is True
        flood = [client.post("/api/studies/tiny/join", json={"recruiting": {"PROLIFIC_PID": "flooder"}})
                 for _ in range(FLOOD)]
        assert {r.status_code for r in flood} == {409}
    reports = rows(server, "device_check")
    assert len(reports) == DEVICE_REPORTS.limit
    assert reports[-1].payload["dropped"] == FLOOD - DEVICE_REPORTS.limit, "the excess is counted"
    refused = rows(server, "join_refused")
    assert len(refused) == REFUSED_JOINS.limit and refused[-1].payload["dropped"] == FLOOD - REFUSED_JOINS.limit
