"""The dashboard is served at ``/admin/`` from ``static/admin/`` (``/admin`` redirects there); the page itself
holds no data — everything it shows comes from the token-protected admin API."""

from __future__ import annotations

from pathlib import Path

import httpx

STATIC = Path(__file__).resolve().parents[2] / "static"


def test_the_dashboard_is_served_at_admin(live_server, study_file):
    server = live_server([study_file()], static_dir=STATIC)
    with httpx.Client(base_url=server.url) as client:
        moved = client.get("/admin")
        page = client.get("/admin/")
        script = client.get("/admin/js/main.js")
        participant_page = client.get("/")
    assert moved.status_code in (301, 302, 307, 308) and moved.headers["location"].endswith("/admin/")
    assert page.status_code == 200 and page.headers["content-type"].startswith("text/html")
    assert '<script type="module" src="/admin/js/main.js">' in page.text and "tiny" not in page.text
    assert script.status_code == 200 and "javascript" in script.headers["content-type"]
    assert "/admin/" not in participant_page.text, "the participant's page does not point to the dashboard"
