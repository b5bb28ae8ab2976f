"""``GET /healthz``: 200 when the store answers, 503 otherwise; ``GET /api/protocol``: the websocket
protocol's JSON schemas (for client authors)."""

from __future__ import annotations

import asyncio
from typing import Any

from fastapi import APIRouter
from fastapi.responses import JSONResponse

from server.deps import ServicesDep
from server.protocol import PROTOCOL_VERSION
from server.protocol.client import client_adapter
from server.protocol.server import server_adapter

router = APIRouter()


@router.get("/healthz")
async def healthz(services: ServicesDep) -> JSONResponse:
    ok = await asyncio.to_thread(services.store.ping)
    body = {"status": "ok" if ok else "unavailable", "store": services.store.dialect,
            "live_trials": len(services.registry.games), "pending_rows": services.writer.pending}
    return JSONResponse(body, status_code=200 if ok else 503)


@router.get("/api/protocol")
def protocol() -> dict[str, Any]:
    return {"version": PROTOCOL_VERSION, "client_messages": client_adapter.json_schema(),
            "server_messages": server_adapter.json_schema()}
