"""``/healthz`` answers 200 while the store answers and 503 when it does not; ``/api/protocol`` gives the
message schemas."""

from __future__ import annotations

import dataclasses

import httpx

from store.engine import Store


def test_healthz_follows_the_store(live_server, study_file):
    server = live_server([study_file()])
    ok = httpx.get(server.url + "/healthz")
    assert ok.status_code == 200 and ok.json()["status"] == "ok" and ok.json()["live_trials"] == 0
    services = server.app.state.services
    broken = Store("postgresql+psycopg://postgres@127.0.0.1:1/nothing?connect_timeout=1")
    server.app.state.services = dataclasses.replace(services, store=broken)
    try:
        down = httpx.get(server.url + "/healthz", timeout=10)
    finally:
        server.app.state.services = services
        broken.dispose()
    assert down.status_code == 503 and down.json()["status"] == "unavailable"


def test_the_protocol_schemas_are_published(live_server, study_file):
    server = live_server([study_file()])
    body = httpx.get(server.url + "/api/protocol").json()
    assert body["version"] == 1
    text = str(body["client_messages"])
    assert all(kind in text for kind in ("select_subtask", "interrupt", "heartbeat", "focus", "blur", "idle"))
    assert all(kind in str(body["server_messages"]) for kind in ("hello", "state", "ack", "pong", "error",
                                                                   "trial_end"))
