"""How many event rows one participant can make the store write by flooding their game socket.

A scripted client joins a study, opens its round and sends ``focus`` messages as fast as the server answers
them for ``--seconds``; the store's event rows of that trial are then counted. Run twice in one process, on one
machine: with the server's per-trial event budget (``server/game/budget.py``) and with it lifted (what the
server did before it), so the two figures are measured side by side. The server runs in this process (uvicorn
in a thread, in-process robots, a temporary SQLite store).

    .venv/bin/python benchmarks/load/event_flood.py --seconds 10
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import json
import tempfile
import threading
import time
from collections import Counter
from pathlib import Path
from typing import Any
from unittest.mock import patch

import httpx
import uvicorn
import yaml
from pydantic import SecretStr
from websockets.asyncio.client import connect

import server.game.link as link
from server.app import create_app
from server.game.budget import EventBudget
from server.settings import Settings
from store.tables import EventRow

STUDY = {"id": "flood", "title": "Flood", "kitchens": ["practice"], "robots": ["stay"], "factors": ["robot"],
         "timing": {"tick_rate_hz": 5}, "world": {"orders": 1, "horizon": 100000, "kb_delay": 1},
         "questionnaires": [{"id": "q", "items": [{"id": "a", "text": "A", "scale": {"min": 1, "max": 5}}]}]}


async def flood(url: str, seconds: float) -> tuple[int, int, float]:
    """Join, open the round, send ``focus`` for ``seconds``; (trial id, messages sent, seconds taken)."""
    async with httpx.AsyncClient(base_url=url, timeout=30) as http:
        token = (await http.post("/api/studies/flood/join", json={})).json()["token"]
        headers = {"Authorization": f"Bearer {token}"}
        await http.post("/api/session/consent", json={"accept": True}, headers=headers)
        await http.post("/api/session/instructions_done", headers=headers)
    async with connect(url.replace("http", "ws", 1) + f"/ws/play?token={token}", max_queue=None) as ws:
        hello = json.loads(await ws.recv())
        sent = answered = 0
        start = time.monotonic()
        while time.monotonic() - start < seconds:
            for _ in range(50):
                sent += 1
                await ws.send(json.dumps({"v": 1, "seq": sent, "type": "focus"}))
            while answered < sent:  # every message is answered (ack or error) before the next batch
                if json.loads(await ws.recv())["type"] in ("ack", "error"):
                    answered += 1
        return int(hello["trial"]["id"]), sent, time.monotonic() - start


def measure(seconds: float, budget: bool, folder: Path) -> dict[str, Any]:
    study = folder / "flood.yaml"
    study.write_text(yaml.safe_dump(STUDY), encoding="utf-8")
    settings = Settings(database_url=f"sqlite:///{folder / ('budget' if budget else 'unlimited')}.sqlite3",
                        study_files=(study,), robot_workers=0, admin_token=SecretStr("bench"), flush_interval_s=0.2,
                        static_dir=folder / "no-static", join_rate_per_minute=0)
    # The participant's link makes its budget as the game starts; lifted, the server is as it was before it had one.
    lifted = patch.object(link, "EventBudget", lambda: EventBudget(rate=1e12, burst=10**12))
    with contextlib.nullcontext() if budget else lifted:
        return run_flood(settings, seconds, budget)


def run_flood(settings: Settings, seconds: float, budget: bool) -> dict[str, Any]:
    app = create_app(settings)
    server = uvicorn.Server(uvicorn.Config(app, host="127.0.0.1", port=0, log_level="error", lifespan="on"))
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    while not server.started:
        time.sleep(0.02)
    url = f"http://127.0.0.1:{server.servers[0].sockets[0].getsockname()[1]}"
    try:
        trial, sent, elapsed = asyncio.run(flood(url, seconds))
        time.sleep(1.0)  # the writer's last batch (disconnect, drop counts)
        with app.state.services.store.transaction() as session:
            rows = session.query(EventRow).filter_by(trial_id=trial).all()
            kinds = Counter(row.kind for row in rows)
            dropped = sum(row.payload["dropped"] for row in rows if row.kind == "events_dropped")
    finally:
        server.should_exit = True
        thread.join(timeout=30)
    return {"budget": budget, "sent": sent, "seconds": elapsed, "rows": len(rows), "focus_rows": kinds["focus"],
            "events_dropped_rows": kinds["events_dropped"], "drops_counted": dropped}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seconds", type=float, default=10.0)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        for budget in (False, True):
            r = measure(args.seconds, budget, Path(tmp))
            print(f"{'with the budget   ' if budget else 'budget lifted     '} {r['sent']} focus messages in "
                  f"{r['seconds']:.1f} s ({r['sent'] / r['seconds']:.0f}/s) → {r['rows']} event rows "
                  f"({r['rows'] / r['seconds']:.1f} rows/s; focus {r['focus_rows']}, events_dropped "
                  f"{r['events_dropped_rows']}, drops counted {r['drops_counted']})")


if __name__ == "__main__":
    main()
