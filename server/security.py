"""Security at the HTTP edge: response headers on every page and API answer, and a per-address join limit.

- :class:`SecurityHeaders` (pure ASGI middleware) adds to every HTTP response ``X-Content-Type-Options:
  nosniff``, ``Referrer-Policy: no-referrer``, ``X-Frame-Options: DENY``, ``Cross-Origin-Opener-Policy:
  same-origin`` and a Content-Security-Policy that lets a page load only this origin's scripts, styles,
  images, data and websocket (no inline scripts, no ``<style>`` elements, no ``eval``, no plugins, no
  framing, forms and ``<base>`` pinned). The client (``static/``) is plain ES modules and stylesheets; the one
  exception is ``style-src-attr 'unsafe-inline'``: the questionnaire sets a CSS variable through a ``style``
  attribute (``static/js/pages/questionnaire.js``); style attributes cannot run code, and the exception can go
  once that uses ``element.style.setProperty``. FastAPI's interactive docs (``/docs``, ``/redoc``) load
  their UI from a CDN with an inline script; they get only ``frame-ancestors 'none'``.
- :class:`JoinLimiter` is a token bucket per client address: ``rate`` joins per minute, bursts up to the
  same number, refilled continuously. The route dependency :func:`limit_joins` answers ``429 {"detail":
  {"code": "rate_limited", …}}`` with ``Retry-After`` once an address has spent its bucket. The address is
  the socket peer, or — only when uvicorn trusts the proxy (``FORWARDED_ALLOW_IPS``, default 127.0.0.1) —
  the ``X-Forwarded-For`` client (see ``docs/operations.md``). Buckets live in this process: with several
  processes the limit applies per process.
- :class:`BodyLimit` (pure ASGI middleware) refuses request bodies over ``max_body_bytes`` (default 64 KiB)
  with ``413 {"detail": {"code": "too_large", …}}``: at once when ``Content-Length`` says so (the body is
  never read), or as soon as a streamed body passes the limit (reading stops there). Nothing of the body is
  echoed.
"""

from __future__ import annotations

import json
import math
import threading
import time
from collections import OrderedDict
from collections.abc import Callable

from fastapi import FastAPI
from starlette.requests import HTTPConnection
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from server.errors import ApiError

PAGE_CSP = "; ".join((
    "default-src 'self'",
    "script-src 'self'",
    "style-src 'self'",
    "style-src-attr 'unsafe-inline'",
    "img-src 'self' data:",
    "font-src 'self'",
    "connect-src 'self'",
    "object-src 'none'",
    "base-uri 'none'",
    "form-action 'self'",
    "frame-ancestors 'none'",
))
DOCS_CSP = "frame-ancestors 'none'"
DOCS_PATHS = ("/docs", "/redoc")
COMMON_HEADERS = (
    (b"x-content-type-options", b"nosniff"),
    (b"referrer-policy", b"no-referrer"),
    (b"x-frame-options", b"DENY"),
    (b"cross-origin-opener-policy", b"same-origin"),
)
MAX_TRACKED_ADDRESSES = 50_000


class SecurityHeaders:
    """Adds the security headers to every HTTP response (websockets pass through untouched)."""

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        path: str = scope.get("path", "")
        csp = DOCS_CSP if path.startswith(DOCS_PATHS) else PAGE_CSP
        extra = [*COMMON_HEADERS, (b"content-security-policy", csp.encode())]

        async def send_with_headers(message: Message) -> None:
            if message["type"] == "http.response.start":
                present = {name.lower() for name, _ in message.get("headers", [])}
                message["headers"] = [*message.get("headers", []),
                                      *((name, value) for name, value in extra if name not in present)]
            await send(message)

        await self.app(scope, receive, send_with_headers)


def _too_large(limit: int) -> bytes:
    return json.dumps({"detail": {"code": "too_large",
                                  "message": f"the request body is larger than {limit} bytes"}}).encode()


class BodyLimit:
    """Answers 413 to HTTP requests whose body is over ``limit`` bytes, without reading (or echoing) it.

    A streamed body (no ``Content-Length``) is counted as the app reads it; past the limit the 413 is sent at
    once and the app is told the client went away (whatever it does then is dropped)."""

    def __init__(self, app: ASGIApp, limit: int) -> None:
        self.app, self.limit = app, limit

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        declared = dict(scope.get("headers", [])).get(b"content-length")
        if declared is not None and (not declared.strip().isdigit() or int(declared) > self.limit):
            await self._refuse(send)
            return
        seen = 0
        started = refused = False

        async def counted_receive() -> Message:
            nonlocal seen, refused
            if refused:
                return {"type": "http.disconnect"}
            message = await receive()
            if message["type"] == "http.request":
                seen += len(message.get("body", b""))
                if seen > self.limit and not started:
                    refused = True
                    await self._refuse(send)
                    return {"type": "http.disconnect"}
            return message

        async def tracked_send(message: Message) -> None:
            nonlocal started
            if refused:
                return
            started = started or message["type"] == "http.response.start"
            await send(message)

        try:
            await self.app(scope, counted_receive, tracked_send)
        except Exception:
            if not refused:
                raise

    async def _refuse(self, send: Send) -> None:
        body = _too_large(self.limit)
        await send({"type": "http.response.start", "status": 413,
                    "headers": [(b"content-type", b"application/json"), (b"content-length", str(len(body)).encode()),
                                (b"connection", b"close")]})
        await send({"type": "http.response.body", "body": body})


class JoinLimiter:
    """Token buckets keyed by client address: ``rate`` joins per minute with bursts of ``rate``; ``rate`` 0
    switches the limit off. Thread-safe; at most :data:`MAX_TRACKED_ADDRESSES` buckets (the least recently
    used are forgotten, which only ever lets an address join sooner)."""

    def __init__(self, rate: int, clock: Callable[[], float] = time.monotonic) -> None:
        self.rate = rate
        self._clock = clock
        self._buckets: OrderedDict[str, tuple[float, float]] = OrderedDict()
        self._lock = threading.Lock()

    def take(self, address: str) -> float:
        """Spend one join for ``address``: 0 when allowed, else the seconds until the next one is."""
        if self.rate <= 0:
            return 0.0
        per_second = self.rate / 60.0
        now = self._clock()
        with self._lock:
            tokens, last = self._buckets.pop(address, (float(self.rate), now))
            tokens = min(float(self.rate), tokens + (now - last) * per_second)
            wait = 0.0 if tokens >= 1.0 else (1.0 - tokens) / per_second
            self._buckets[address] = (tokens - 1.0 if wait == 0.0 else tokens, now)
            while len(self._buckets) > MAX_TRACKED_ADDRESSES:
                self._buckets.popitem(last=False)
        return wait


def client_address(conn: HTTPConnection) -> str:
    return conn.client.host if conn.client is not None else "unknown"


async def limit_joins(conn: HTTPConnection) -> None:
    """Route dependency of ``POST /api/studies/{id}/join``: 429 once the caller's address is over its limit."""
    limiter: JoinLimiter = conn.app.state.join_limiter
    wait = limiter.take(client_address(conn))
    if wait > 0:
        raise ApiError(429, "rate_limited", "too many joins from this address; try again shortly",
                       headers={"Retry-After": str(max(1, math.ceil(wait)))})


def install(app: FastAPI, join_rate_per_minute: int, max_body_bytes: int) -> None:
    """Add the security headers, the request body limit and the join limiter to ``app``."""
    app.state.join_limiter = JoinLimiter(join_rate_per_minute)
    app.add_middleware(BodyLimit, limit=max_body_bytes)
    app.add_middleware(SecurityHeaders)
