"""Text a request may carry: every string of a JSON body (keys and values, at any depth) must be storable.

JSON can spell characters no store keeps: a lone UTF-16 surrogate (``"\\ud800"``, which has no UTF-8 form, so
neither the response nor SQLite nor PostgreSQL can write it) and NUL (``"\\u0000"``, which PostgreSQL's
``text`` and ``jsonb`` refuse). A body holding either is refused before any route runs, with a 422 that
names the field (``loc`` as in FastAPI's own validation errors), so the same input gets the same answer on
every route and every store (docs/protocol.md, "Bad input").
"""

from __future__ import annotations

from typing import Any

from fastapi import Request
from fastapi.exceptions import RequestValidationError

MAX_DEPTH = 64
"""Deeper bodies are left to the schemas (no participant schema nests this deep)."""


def text_problem(value: str) -> str | None:
    """Why ``value`` cannot be stored, or ``None``."""
    if "\x00" in value:
        return "the text holds a NUL character (\\u0000)"
    try:
        value.encode("utf-8")
    except UnicodeEncodeError:
        return "the text holds a lone UTF-16 surrogate (\\ud800-\\udfff), which is not a character"
    return None


def first_problem(value: Any, loc: tuple[str | int, ...] = ("body",),
                  depth: int = 0) -> tuple[tuple[str | int, ...], str] | None:
    """The location and reason of the first unstorable string in a parsed JSON value, or ``None``."""
    if depth > MAX_DEPTH:
        return None
    if isinstance(value, str):
        reason = text_problem(value)
        return (loc, reason) if reason else None
    if isinstance(value, dict):
        for key, item in value.items():
            reason = text_problem(key) if isinstance(key, str) else None
            if reason:
                return (*loc, safe(key)), "a field name: " + reason
            found = first_problem(item, (*loc, key), depth + 1)
            if found:
                return found
    if isinstance(value, list):
        for index, item in enumerate(value):
            found = first_problem(item, (*loc, index), depth + 1)
            if found:
                return found
    return None


def safe(value: str) -> str:
    """``value`` with lone surrogates written as ``\\udxxx`` escapes and NUL as ``\\x00`` (printable, storable)."""
    return value.encode("utf-8", "backslashreplace").decode("utf-8").replace("\x00", "\\x00")


async def storable_body(request: Request) -> None:
    """A router dependency: 422 ``string_unstorable`` naming the first field whose text cannot be stored."""
    body = await request.body()
    if not body:
        return
    try:
        value = await request.json()
    except (ValueError, RecursionError):
        return  # not JSON: the route's own parsing answers
    found = first_problem(value)
    if found is not None:
        loc, reason = found
        raise RequestValidationError([{"type": "string_unstorable", "loc": loc, "msg": reason}])

