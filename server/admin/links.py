"""Recruiting links of a study: the participant link with the study's URL parameters as Prolific-style
placeholders (``NAME={{%NAME%}}``, which Prolific fills in per participant), a signed test-run link
(:mod:`server.admin.test_links`), and where participants end (the codes and the redirect URLs with the code
filled in).

The landing page (``static/js/landing.js``) reads ``study``, ``new`` and the fragment's ``test`` code, and passes
on only the study's ``recruiting.url_parameters``.
"""

from __future__ import annotations

import time
from datetime import UTC, datetime
from typing import Any
from urllib.parse import quote

from server.admin.test_links import TEST_FRAGMENT, TEST_LINK_DAYS, make_test_code
from study_config.catalog import Catalog, LoadedStudy
from study_config.study.warnings import study_warnings


def placeholder(name: str) -> str:
    return "{{%" + name + "%}}"


def start_banner(catalog: Catalog, base_url: str, key: bytes) -> list[str]:
    """What ``steakhouse serve`` prints at start: each study's participant and test-run links, the admin
    address, and a loud line per shipped placeholder code still in a study (:mod:`server.flow.payment`)."""
    base = base_url.rstrip("/")
    lines = [f"Admin dashboard: {base}/admin/  (token: STEAKHOUSE_ADMIN_TOKEN, or the one logged above)"]
    for loaded in catalog:
        links = study_links(loaded, base, key)
        lines.append(f"Study {loaded.id}: participant link {links['participant']['url']}")
        lines.append(f"{' ' * (len(loaded.id) + 7)}test run         {links['test_run']['url']}")
    for loaded in catalog:
        for warning in study_warnings(loaded.study):
            if warning.code == "placeholder_code":
                lines.append(f"WARNING: study {loaded.id}: {warning.path} is still the shipped placeholder: real "
                             "participants are told the study is not set up for payment and get no code. Set the "
                             "code your recruiting platform gives you (docs/deploy.md).")
    return lines


def study_links(loaded: LoadedStudy, base_url: str, key: bytes, now: float | None = None) -> dict[str, Any]:
    """Paths (relative to the server's root) and absolute URLs on ``base_url``; the test-run links signed with
    ``key`` (:func:`server.admin.test_links.signing_key`), valid for :data:`TEST_LINK_DAYS` from ``now``."""
    study, base = loaded.study, base_url.rstrip("/")
    recruiting = study.recruiting
    study_param = f"study={quote(study.id, safe='')}"
    participant = "/?" + "&".join([study_param] + [f"{n}={placeholder(n)}" for n in recruiting.url_parameters])
    expires = int(now if now is not None else time.time()) + TEST_LINK_DAYS * 86_400
    code = make_test_code(key, study.id, expires)
    test_run = f"/?{study_param}#{TEST_FRAGMENT}={code}"
    fresh = f"/?{study_param}&new=1#{TEST_FRAGMENT}={code}"
    return {
        "study_id": study.id,
        "url_parameters": list(recruiting.url_parameters),
        "participant": {"path": participant, "url": base + participant},
        "test_run": {"path": test_run, "url": base + test_run},
        "fresh_test_run": {"path": fresh, "url": base + fresh},
        "test_link_expires_at": datetime.fromtimestamp(expires, UTC).isoformat(),
        "completion": {"code": recruiting.completion_code, "redirect_url": recruiting.redirect("completion")},
        "screen_out": {"code": recruiting.screen_out_code, "redirect_url": recruiting.redirect("screen_out")},
    }
