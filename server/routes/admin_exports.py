"""The admin download of a study's export (admin bearer token, as the rest of ``/api/admin/``).

``GET /api/admin/studies/{study_id}/export.zip``: the files of ``steakhouse export`` (tidy CSVs and the
data dictionary, see :mod:`analysis.exports.study_export`) in one zip, built from the store at request time. The store
is read on an engine of its own, so a long export never holds the SQLite write lock the game loop needs.
"""

from __future__ import annotations

from typing import Annotated

from fastapi import APIRouter, Depends, Path
from fastapi.responses import Response

from server.deps import ServicesDep, require_admin
from server.errors import ApiError

router = APIRouter(prefix="/api/admin", tags=["admin"], dependencies=[Depends(require_admin)])


@router.get("/studies/{study_id}/export.zip")
def study_export(study_id: Annotated[str, Path(max_length=64)], services: ServicesDep) -> Response:
    from analysis.exports.study_export import export_zip
    from analysis.source.store_reader import UnknownStudyError

    url = services.store.url.render_as_string(hide_password=False)
    try:
        archive = export_zip(url, study_id)
    except UnknownStudyError:
        raise ApiError(404, "unknown_study", "no such study in the store") from None
    return Response(archive, media_type="application/zip",
                    headers={"Content-Disposition": f'attachment; filename="{study_id}_export.zip"'})
