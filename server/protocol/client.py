"""Client → server messages (protocol v1), validated strictly: no coercion, no unknown fields.

Every message is a JSON object ``{"v": 1, "seq": n, "type": ..., ...}`` where ``seq`` is a positive integer,
strictly greater than that of the last message the server accepted on this connection (gaps allowed: a
rejected message does not consume its number).
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field, TypeAdapter

from planner.subtasks import Subtask
from server.protocol.interrupts import Interrupt


class ClientMessage(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True, frozen=True)

    v: Literal[1]
    seq: int = Field(ge=1, le=2**53)


class SelectSubtask(ClientMessage):
    """Choose a subtask: the avatar walks there by the shortest path and interacts; replaces the current one."""

    type: Literal["select_subtask"]
    subtask: Subtask


class InterruptMessage(ClientMessage):
    """An interrupt action, applied at the next tick (``stop`` cancels the subtask at once)."""

    type: Literal["interrupt"]
    action: Interrupt


class Heartbeat(ClientMessage):
    """Keep-alive and latency probe; answered by ``pong`` echoing ``client_time`` (ms, client clock)."""

    type: Literal["heartbeat"]
    client_time: float = Field(allow_inf_nan=False)
    """Finite: ``NaN`` and ``Infinity`` (which Python's JSON accepts) could not be echoed back as JSON."""


class Focus(ClientMessage):
    """The game tab got focus."""

    type: Literal["focus"]


class Blur(ClientMessage):
    """The game tab lost focus (tab switch, window change)."""

    type: Literal["blur"]


class Idle(ClientMessage):
    """No input for ``idle_ms`` milliseconds (the client decides when to report)."""

    type: Literal["idle"]
    idle_ms: int = Field(ge=0)


AnyClientMessage = Annotated[SelectSubtask | InterruptMessage | Heartbeat | Focus | Blur | Idle,
                             Field(discriminator="type")]
CLIENT_TYPES: tuple[str, ...] = ("select_subtask", "interrupt", "heartbeat", "focus", "blur", "idle")
client_adapter: TypeAdapter[AnyClientMessage] = TypeAdapter(AnyClientMessage)
