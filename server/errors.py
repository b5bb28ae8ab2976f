"""Typed API errors: every refusal has an HTTP status, a stable ``code`` and a readable ``message``.

Body: ``{"detail": {"code": ..., "message": ...}}`` (422 answer problems: ``{"detail": [problems]}``,
the shape of FastAPI's own validation errors). Nothing about other participants or internals is included,
and a request's own input is quoted at most as a short excerpt (:data:`EXCERPT_CHARS` characters): a large
body is never echoed back, and a non-finite number (``NaN``, ``Infinity``) is quoted as text.
"""

from __future__ import annotations

import json
import math
from typing import Any

from fastapi import FastAPI, Request
from fastapi.encoders import jsonable_encoder
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse

from server.text_input import safe

EXCERPT_CHARS = 60
"""The most of a request's own input an error body quotes."""


class ApiError(Exception):
    def __init__(self, status: int, code: str, message: str, headers: dict[str, str] | None = None) -> None:
        super().__init__(message)
        self.status, self.code, self.message, self.headers = status, code, message, headers


class Conflict(Exception):
    """A request the current state does not allow (HTTP 409): ``code``, the message, and ``extra`` fields that say
    which state and which action (the participant's state machine raises one, :mod:`server.flow.progress`)."""

    code = "conflict"

    def __init__(self, message: str, extra: dict[str, str] | None = None) -> None:
        super().__init__(message)
        self.extra = extra or {}


class AnswerProblems(Exception):
    def __init__(self, problems: list[dict[str, Any]]) -> None:
        super().__init__(f"{len(problems)} problem(s) with the answers")
        self.problems = problems


def unauthorized(message: str = "a valid token is required") -> ApiError:
    return ApiError(401, "unauthorized", message, headers={"WWW-Authenticate": "Bearer"})


def install(app: FastAPI) -> None:
    """Register the handlers that turn these exceptions into responses."""

    async def api_error(_: Request, exc: Exception) -> JSONResponse:
        assert isinstance(exc, ApiError)
        return JSONResponse({"detail": {"code": exc.code, "message": exc.message}}, exc.status,
                            headers=exc.headers)

    async def conflict(_: Request, exc: Exception) -> JSONResponse:
        assert isinstance(exc, Conflict)
        return JSONResponse({"detail": {"code": exc.code, "message": str(exc), **exc.extra}}, 409)

    async def answers(_: Request, exc: Exception) -> JSONResponse:
        assert isinstance(exc, AnswerProblems)
        return JSONResponse({"detail": exc.problems}, 422)

    async def invalid_request(_: Request, exc: Exception) -> JSONResponse:
        assert isinstance(exc, RequestValidationError)
        return JSONResponse({"detail": [_problem(error) for error in exc.errors()]}, 422)

    app.add_exception_handler(ApiError, api_error)
    app.add_exception_handler(Conflict, conflict)
    app.add_exception_handler(AnswerProblems, answers)
    app.add_exception_handler(RequestValidationError, invalid_request)


def _problem(error: Any) -> dict[str, Any]:
    """One of FastAPI's validation problems as JSON: its location, type and message, the input quoted only as
    an excerpt, and the context as short text (it may hold exceptions or non-finite numbers)."""
    out: dict[str, Any] = {"type": str(error.get("type", "")), "loc": [_scalar(part) for part in error.get("loc", ())],
                           "msg": excerpt(error.get("msg", ""), 200)}
    if "input" in error:
        out["input"] = _quoted(error["input"])
    if error.get("ctx"):
        out["ctx"] = {str(key): _quoted(value) for key, value in error["ctx"].items()}
    encoded: dict[str, Any] = jsonable_encoder(out)
    return encoded


def excerpt(value: Any, limit: int = EXCERPT_CHARS) -> str:
    """``value`` as text, cut to ``limit`` characters (with "…" when cut)."""
    if isinstance(value, bytes):
        value = value[: limit * 4].decode("utf-8", errors="replace")
    if not isinstance(value, str):
        try:
            value = json.dumps(value, allow_nan=True, default=str)[: limit * 4]
        except ValueError:
            value = "…"
    text = safe(value)
    return text if len(text) <= limit else text[: limit - 1] + "…"


def _scalar(value: Any) -> str | int:
    return value if isinstance(value, int) and not isinstance(value, bool) and abs(value) < 2**53 else excerpt(value)


def _quoted(value: Any) -> Any:
    """A short JSON-safe quote of ``value``: small finite numbers, booleans and ``None`` as they are,
    everything else as an excerpt of its text."""
    if value is None or isinstance(value, bool):
        return value
    if isinstance(value, int) and abs(value) < 2**53:
        return value
    if isinstance(value, float) and math.isfinite(value):
        return value
    if isinstance(value, float):
        return str(value)
    return excerpt(value)
