"""Test-run links: only the experimenter starts a test run (docs/admin.md, "Recruiting links").

A test run is a participant who is not counted for assignment, is left out of the exports, skips the study's
required recruiting id and never sees the study's real completion code. So a participant's own request can never
ask for one: the join's ``test_link`` must be a code the admin signed (the dashboard's recruiting links, or the
links ``steakhouse serve`` prints at start), ``/?study=<id>#test=<code>``, the code in the URL's fragment (browsers
never send it to a server, so it stays out of access logs).

``code = <expiry, unix seconds>.<signature>``, an HMAC-SHA256 over the study id and the expiry, keyed by a secret
derived from the admin token (every server process of a deployment agrees). A link works for any number of test
runs until it expires (:data:`TEST_LINK_DAYS`); one for another study, an altered or an expired one is refused.
"""

from __future__ import annotations

import base64
import hashlib
import hmac

TEST_FRAGMENT = "test"
"""The landing URL's fragment key that carries the code."""
TEST_LINK_DAYS = 7
"""How long a test link works."""
_CONTEXT = b"steakhouse.test-link.v1\0"


def signing_key(admin_token: str) -> bytes:
    return hashlib.sha256(_CONTEXT + admin_token.encode("utf-8")).digest()


def _signature(secret: bytes, study_id: str, expires: int) -> str:
    mac = hmac.new(secret, f"{study_id}.{expires}".encode(), hashlib.sha256).digest()
    return base64.urlsafe_b64encode(mac).decode().rstrip("=")


def make_test_code(secret: bytes, study_id: str, expires: int) -> str:
    return f"{expires}.{_signature(secret, study_id, expires)}"


def verify_test_code(secret: bytes, code: str, study_id: str, now: float) -> bool:
    """Whether ``code`` is a test link the admin signed for ``study_id`` that has not expired."""
    expires, _, signature = code.partition(".")
    if not expires.isdigit() or len(expires) > 12 or not signature:
        return False
    expected = _signature(secret, study_id, int(expires))
    return now <= int(expires) and hmac.compare_digest(expected, signature)
