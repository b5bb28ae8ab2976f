"""The browser client (``static/``) at ``/``: files as they are, and ``index.html`` for any other path
outside ``/api`` and ``/ws`` (the client routes its pages itself). Mounted only when the folder has files."""

from __future__ import annotations

from pathlib import Path

from starlette.exceptions import HTTPException
from starlette.responses import Response
from starlette.staticfiles import StaticFiles
from starlette.types import Scope

_NEVER_FALLBACK = ("api/", "ws/", "healthz")


class ClientFiles(StaticFiles):
    async def get_response(self, path: str, scope: Scope) -> Response:
        try:
            return await super().get_response(path, scope)
        except HTTPException as exc:
            if exc.status_code != 404 or path.startswith(_NEVER_FALLBACK) or path == "api":
                raise
            return await super().get_response("index.html", scope)


def client_files(folder: Path) -> ClientFiles:
    return ClientFiles(directory=folder, html=True)
