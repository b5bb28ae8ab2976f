"""Pilot participants: only the admin can join one; they are balanced among themselves and never move the
assignment of real participants; the admin shows them apart."""

from __future__ import annotations

from typing import Any

import httpx
import pytest

ADMIN = {"Authorization": "Bearer admin-secret"}


@pytest.fixture
def client(live_server, study_file):
    server = live_server([study_file(robots=["stay", "baseline"], world={"orders": 1, "horizon": 5})])
    with httpx.Client(base_url=server.url, timeout=30) as client:
        yield client


def join(client: httpx.Client, name: str, pilot: bool = False, headers: dict[str, str] | None = None) -> httpx.Response:
    body: dict[str, Any] = {"recruiting": {"PROLIFIC_PID": name}}
    if pilot:
        body["pilot"] = {"pace": "fast"}
    return client.post("/api/studies/tiny/join", json=body, headers=headers or {})


def order_of(client: httpx.Client, response: httpx.Response) -> int:
    """The order the admin sees for the participant just joined (the join answer itself never names it)."""
    public_id = response.json()["participant_id"]
    people: list[dict[str, Any]] = client.get("/api/admin/participants", headers=ADMIN).json()
    order: int = next(p["order_index"] for p in people if p["participant_id"] == public_id)
    return order


def test_a_participant_cannot_make_themselves_a_pilot(client) -> None:
    for headers in ({}, {"Authorization": "Bearer not-the-admin"}):
        response = join(client, "p1", pilot=True, headers=headers)
        assert response.status_code == 403
        assert response.json()["detail"]["code"] == "pilot_needs_admin"
    assert client.get("/api/admin/participants", headers=ADMIN).json() == []


def test_pilots_leave_the_balance_of_real_participants_untouched(client) -> None:
    orders = [order_of(client, join(client, f"pilot-{i}", pilot=True, headers=ADMIN)) for i in range(3)]
    assert orders == [0, 1, 0], "pilots are balanced among themselves"
    assert order_of(client, join(client, "real-1")) == 0, "the first real participant still gets the least-filled order"
    assert order_of(client, join(client, "real-2")) == 1
    study = next(s for s in client.get("/api/admin/studies", headers=ADMIN).json() if s["id"] == "tiny")
    assert [o["counted"] for o in study["orders"]] == [1, 1]
    assert [o["pilots"] for o in study["orders"]] == [2, 1]
    assert [o["assigned"] for o in study["orders"]] == [1, 1], "pilots are not among the assigned participants"
    people = client.get("/api/admin/participants", headers=ADMIN).json()
    assert sorted(p["pilot"] for p in people) == [False, False, True, True, True]


def test_a_pilot_rejoining_stays_the_same_pilot_and_nobody_else_can_take_its_place(client) -> None:
    first = join(client, "pilot-a", pilot=True, headers=ADMIN).json()
    again = join(client, "pilot-a", pilot=True, headers=ADMIN).json()
    assert again["rejoined"] and again["participant_id"] == first["participant_id"]
    taken = join(client, "pilot-a")
    assert taken.status_code == 409 and taken.json()["detail"]["code"] == "recruit_id_taken"
    join(client, "real-b")
    assert join(client, "real-b", pilot=True, headers=ADMIN).status_code == 409
