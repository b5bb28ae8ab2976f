"""Typed API errors: every refusal has an HTTP status, a stable ``code`` and a readable ``message``.

Body: ``{"detail": {"code": ..., "message": ...}}`` (422 answer problems: ``{"detail": [problems]}``,
the shape of FastAPI's own validation errors). Nothing about other participants or internals is included.
"""

from __future__ import annotations

from typing import Any

from fastapi import FastAPI, Request
from fastapi.encoders import jsonable_encoder
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse

from server.flow.progress import IllegalTransition


class ApiError(Exception):
    def __init__(self, status: int, code: str, message: str, headers: dict[str, str] | None = None) -> None:
        super().__init__(message)
        self.status, self.code, self.message, self.headers = status, code, message, headers


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

    async def illegal(_: Request, exc: Exception) -> JSONResponse:
        assert isinstance(exc, IllegalTransition)
        return JSONResponse({"detail": {"code": "illegal_transition", "message": str(exc),
                                        "state": exc.phase.value, "action": exc.move.value}}, 409)

    async def answers(_: Request, exc: Exception) -> JSONResponse:
        assert isinstance(exc, AnswerProblems)
        return JSONResponse({"detail": exc.problems}, 422)

    async def invalid_request(_: Request, exc: Exception) -> JSONResponse:
        assert isinstance(exc, RequestValidationError)
        return JSONResponse({"detail": jsonable_encoder(_printable(exc.errors()))}, 422)

    app.add_exception_handler(ApiError, api_error)
    app.add_exception_handler(IllegalTransition, illegal)
    app.add_exception_handler(AnswerProblems, answers)
    app.add_exception_handler(RequestValidationError, invalid_request)


def _printable(value: Any) -> Any:
    """FastAPI's validation problems with any raw bytes echoed back as text: a body that is not UTF-8 would
    otherwise make FastAPI's own 422 handler fail with a 500."""
    if isinstance(value, bytes):
        return value.decode("utf-8", errors="replace")
    if isinstance(value, dict):
        return {key: _printable(item) for key, item in value.items()}
    if isinstance(value, list | tuple):
        return [_printable(item) for item in value]
    return value
