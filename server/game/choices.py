"""What an accepted participant message does to their cook (docs/protocol.md, the client's messages).

- ``select_subtask``: the cook takes the subtask (logged with whether the page offered it); one refused at once
  (it could not even begin) is told to the participant with its reason (``server.game.blocked``).
- ``interrupt``: the key's action waits in the cook's queue (logged with the subtask it interrupted); a fourth one
  waiting is refused as ``queue_full``, nothing changed.
- ``focus``, ``blur``, ``idle``: logged only.

A choice or key that leaves the cook something to do ends the participant's idle stretch (``acted``). Messages are
applied between ticks (the loop and the handlers share one event loop thread), so an interrupt acts at the next tick.
"""

from __future__ import annotations

from collections.abc import Callable

from server.game.blocked import Blocked
from server.game.engine import TrialEngine
from server.game.records import EventLog
from server.protocol.client import AnyClientMessage, Blur, Focus, Idle, InterruptMessage, SelectSubtask
from server.protocol.inbound import ProtocolError
from server.protocol.server import Ack


def apply_choice(message: AnyClientMessage, engine: TrialEngine, *, log: EventLog,
                 blocked: Callable[[Blocked], None], acted: Callable[[], None]) -> Ack:
    """Apply ``message`` (checked, not a heartbeat) to ``engine``'s controller; the ``ack`` to answer it with.
    Raises :class:`ProtocolError` when the message is refused."""
    controller = engine.controller
    if isinstance(message, SelectSubtask):
        offered = controller.available(engine.world, engine.kb)
        refused = controller.select(message.subtask, engine.world.human.held)
        log("select_subtask", {"seq": message.seq, "subtask": message.subtask.value,
                               "available": message.subtask in offered})
        if refused is not None:
            blocked(refused)
    elif isinstance(message, InterruptMessage):
        before = controller.subtask
        if not controller.interrupt(message.action):
            raise ProtocolError("queue_full", "three interrupts are already waiting", message.seq)
        log("interrupt", {"seq": message.seq, "action": message.action.value,
                          "subtask": before.value if before else None})
    elif isinstance(message, Focus | Blur):
        log(message.type, {"seq": message.seq})
    elif isinstance(message, Idle):
        log("idle", {"seq": message.seq, "idle_ms": message.idle_ms})
    if isinstance(message, SelectSubtask | InterruptMessage) and controller.has_action():
        acted()
    return Ack(ack=message.seq, subtask=controller.subtask.value if controller.subtask else None,
               queued=len(controller.queue))
