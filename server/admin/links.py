"""Recruiting links of a study: the participant link with the study's URL parameters as Prolific-style
placeholders (``NAME={{%NAME%}}``, which Prolific fills in per participant), a test-run link, and where
participants end (the codes and the redirect URLs with the code filled in).

The landing page (``static/js/landing.js``) reads ``study``, ``test_run`` and ``new`` and passes on only the
study's ``recruiting.url_parameters``.
"""

from __future__ import annotations

from typing import Any
from urllib.parse import quote

from server.catalog import LoadedStudy


def placeholder(name: str) -> str:
    return "{{%" + name + "%}}"


def study_links(loaded: LoadedStudy, base_url: str) -> dict[str, Any]:
    """Paths (relative to the server's root) and absolute URLs on ``base_url``."""
    study, base = loaded.study, base_url.rstrip("/")
    recruiting = study.recruiting
    study_param = f"study={quote(study.id, safe='')}"
    participant = "/?" + "&".join([study_param] + [f"{n}={placeholder(n)}" for n in recruiting.url_parameters])
    test_run = f"/?{study_param}&test_run=1"
    fresh = f"{test_run}&new=1"
    return {
        "study_id": study.id,
        "url_parameters": list(recruiting.url_parameters),
        "participant": {"path": participant, "url": base + participant},
        "test_run": {"path": test_run, "url": base + test_run},
        "fresh_test_run": {"path": fresh, "url": base + fresh},
        "completion": {"code": recruiting.completion_code, "redirect_url": recruiting.redirect("completion")},
        "screen_out": {"code": recruiting.screen_out_code, "redirect_url": recruiting.redirect("screen_out")},
    }
