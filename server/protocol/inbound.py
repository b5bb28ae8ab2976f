"""Checking one client message, in this order, each failure a typed :class:`ProtocolError`:

1. a text frame (``bad_frame``) of at most ``limit`` UTF-8 bytes (``too_large``);
2. valid JSON (``bad_json``) holding an object (``invalid_message``);
3. ``"v": 1`` (``unsupported_version``) and a positive integer ``seq`` (``invalid_message``);
4. ``seq`` strictly greater than the last accepted one (``bad_seq``: a duplicate or out of order);
5. a known ``type`` (``unknown_type``) whose fields have the right names and types (``invalid_message``).

A rejected message changes nothing; :meth:`Inbound.accept` records the ``seq`` of a message once it has
been applied, so only applied messages consume sequence numbers.
"""

from __future__ import annotations

import json
from typing import Any

from pydantic import ValidationError

from server.protocol.client import CLIENT_TYPES, AnyClientMessage, client_adapter


class ProtocolError(Exception):
    def __init__(self, code: str, message: str, ref: int | None = None) -> None:
        super().__init__(message)
        self.code, self.message, self.ref = code, message, ref


class Inbound:
    """The receiving side of one connection: the size limit and the last accepted sequence number."""

    def __init__(self, limit: int) -> None:
        self.limit = limit
        self.last_seq = 0

    def check(self, text: str | None, data: bytes | None = None) -> AnyClientMessage:
        if text is None:
            raise ProtocolError("bad_frame", "only text frames carrying JSON are accepted")
        size = len(text.encode("utf-8", errors="surrogatepass"))
        if size > self.limit:
            raise ProtocolError("too_large", f"message of {size} bytes exceeds the limit of {self.limit}")
        try:
            raw: Any = json.loads(text)
        except (ValueError, RecursionError) as exc:
            raise ProtocolError("bad_json", f"not valid JSON: {exc}"[:200]) from None
        if not isinstance(raw, dict):
            raise ProtocolError("invalid_message", "a message is a JSON object")
        seq = raw.get("seq")
        ref = seq if _is_seq(seq) else None
        if raw.get("v") != 1 or isinstance(raw.get("v"), bool):
            raise ProtocolError("unsupported_version", "this server speaks protocol version 1 (\"v\": 1)", ref)
        if ref is None:
            raise ProtocolError("invalid_message", "seq must be a positive integer")
        if ref <= self.last_seq:
            raise ProtocolError("bad_seq", f"seq {ref} is not greater than the last accepted {self.last_seq}", ref)
        if raw.get("type") not in CLIENT_TYPES:
            raise ProtocolError("unknown_type", f"unknown type {str(raw.get('type'))[:40]!r}; "
                                                f"known: {', '.join(CLIENT_TYPES)}", ref)
        try:
            return client_adapter.validate_json(text, strict=True)
        except ValidationError as exc:
            problems = "; ".join(f"{'.'.join(str(p) for p in e['loc'][1:]) or 'message'}: {e['msg']}"
                                 for e in exc.errors()[:5])
            raise ProtocolError("invalid_message", problems[:300], ref) from None

    def accept(self, seq: int) -> None:
        self.last_seq = max(self.last_seq, seq)


def _is_seq(value: Any) -> bool:
    return isinstance(value, int) and not isinstance(value, bool) and 1 <= value <= 2**53
