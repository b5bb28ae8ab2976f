"""``/ws/play``: the participant's game connection, authenticated by the participant token (offered as the
subprotocol ``token.<token>`` beside ``steakhouse.v1``, which the server then selects; or ``?token=…``).
Starts or resumes the trial of their current step; one connection per participant (a newer one replaces
the older, which gets ``error: replaced``).

When this server process already runs as many live trials as it can hold on time, the participant first
waits for a slot (``server.game.lobby``): ``waiting`` messages with their place in line and the
expected wait; past the limit ``error`` ``server_full`` (close 4503) and the participant is screened out.

Refusals before the game starts are typed too: ``error`` with code ``unauthorized`` (close 4401), ``device_refused``
(close 4403: the device check on landing refused the participant's device, and a round never opens on it) or
``no_trial`` (close 4409, the participant is not at a trial step); a trial abandoned after the grace window answers
``trial_end`` with status ``abandoned``.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging

from fastapi import APIRouter, WebSocket

from server.deps import SUBPROTOCOL, ServicesDep, find_participant, offered_subprotocols, participant_token
from server.game.connection import Connection
from server.game.registry import GameRegistry, NoTrial, TrialAbandoned
from server.protocol.server import Error, ServerMessage, TrialEnd
from store.tables import ParticipantRow
from study_config.study.device import refused as device_refused

router = APIRouter()
log = logging.getLogger(__name__)


async def _refuse(websocket: WebSocket, message: ServerMessage, code: int) -> None:
    message.seq = 1
    with contextlib.suppress(Exception):
        await websocket.send_text(message.model_dump_json())
        await websocket.close(code=code)


async def _gone(websocket: WebSocket) -> None:
    """Return when the client closes (a waiting client sends nothing else that matters)."""
    while (await websocket.receive())["type"] != "websocket.disconnect":
        pass


async def _admitted(websocket: WebSocket, registry: GameRegistry, participant: ParticipantRow,
                    conn: Connection) -> bool:
    """Wait for a slot if the server is full (``waiting`` messages); ``False`` when the participant left or
    waited too long (then told ``server_full`` and screened out)."""
    ticket = await registry.claim(participant)
    if ticket is None:
        return True
    conn.wait()
    turn = asyncio.ensure_future(registry.lobby.wait_turn(participant, ticket, conn))
    gone = asyncio.ensure_future(_gone(websocket))
    try:
        await asyncio.wait({turn, gone}, return_when=asyncio.FIRST_COMPLETED)
    finally:
        left = gone.done()
        gone.cancel()
        if not turn.done():
            turn.cancel()
        for task in (turn, gone):
            with contextlib.suppress(asyncio.CancelledError, Exception):
                await task
    if turn.cancelled() or turn.exception() is not None:
        conn.broken()
        return False
    if left:
        if turn.result():
            registry.release(participant.id)
        conn.broken()
        return False
    if not turn.result():
        conn.send(Error(code="server_full", message="the study is busy right now; your session ends here"))
        conn.begin_close(4503)
        await conn.wait_closed()
        return False
    return True


@router.websocket("/ws/play")
async def play(websocket: WebSocket, services: ServicesDep) -> None:
    await websocket.accept(subprotocol=SUBPROTOCOL if SUBPROTOCOL in offered_subprotocols(websocket) else None)
    token = participant_token(websocket)
    participant = await asyncio.to_thread(find_participant, services.store, token) if token else None
    if participant is None:
        await _refuse(websocket, Error(code="unauthorized", message="a valid participant token is required"), 4401)
        return
    if device_refused(participant.device):
        await _refuse(websocket, Error(code="device_refused", message="this device cannot take part: please use a "
                                       "computer with a keyboard"), 4403)
        return
    conn = Connection(websocket)
    registry = services.registry
    if not await _admitted(websocket, registry, participant, conn):
        return
    try:
        game = await registry.attach(participant, conn)
    except NoTrial as exc:
        registry.release(participant.id)
        await _refuse(websocket, Error(code="no_trial", message=str(exc)), 4409)
        return
    except TrialAbandoned as exc:
        registry.release(participant.id)
        row, progress = exc.prepared.trial, exc.prepared.progress
        await _refuse(websocket, TrialEnd(status="abandoned", reason="grace_expired", ticks=row.ticks,
                                          delivered=row.delivered, score=row.score,
                                          next=progress.phase.value if progress else "unknown"), 1000)
        return
    except Exception:
        registry.release(participant.id)
        log.exception("cannot start the trial of participant %s", participant.public_id)
        await _refuse(websocket, Error(code="internal", message="the trial could not start; try again later"),
                      1011)
        return
    try:
        while True:
            await conn.room()
            frame = await websocket.receive()
            if frame["type"] == "websocket.disconnect":
                break
            game.handle(conn, frame.get("text"), frame.get("bytes"))
    except Exception as exc:
        log.debug("websocket of trial %d ended: %s", game.meta.trial_id, exc)
    finally:
        conn.broken()
        registry.detach(game, conn)
