"""One-time, expiring resume links: how an experimenter moves a participant to a new device.

A recruiting id is not a password (``docs/protocol.md`` §1): only the browser holding a participant's token
resumes their session. When a participant has to change device, the experimenter makes a resume link in
the admin and sends it to them: ``/?study=<id>#resume=<code>``. The code sits in the URL's fragment, which
browsers never send to a server, so it stays out of access logs.

``code = <public id>.<expiry, unix seconds>.<signature>``, the signature an HMAC-SHA256 over the public id,
the expiry and the participant's current token hash, keyed by a secret derived from the admin token. No
state is kept: redeeming the link gives the participant a new token, which changes the token hash, so the
same link then no longer verifies (one use); after the expiry it is refused as well. A link made before the
participant's token last changed is void for the same reason.
"""

from __future__ import annotations

import base64
import hashlib
import hmac
from dataclasses import dataclass

RESUME_FRAGMENT = "resume"
"""The landing URL's fragment key that carries the code."""
_CONTEXT = b"steakhouse.resume-link.v1\0"


@dataclass(frozen=True)
class ResumeCode:
    """A code read back from a link: whose it is, until when, and its signature."""

    public_id: str
    expires: int
    signature: str


def link_secret(admin_token: str) -> bytes:
    """The signing key: derived from the admin token, so every server process of a deployment agrees."""
    return hashlib.sha256(_CONTEXT + admin_token.encode("utf-8")).digest()


def _signature(secret: bytes, public_id: str, expires: int, token_hash: str) -> str:
    mac = hmac.new(secret, f"{public_id}.{expires}.{token_hash}".encode(), hashlib.sha256).digest()
    return base64.urlsafe_b64encode(mac).decode().rstrip("=")


def make_code(secret: bytes, public_id: str, token_hash: str, expires: int) -> str:
    """The code of a link for the participant ``public_id`` whose token hash is ``token_hash`` now."""
    return f"{public_id}.{expires}.{_signature(secret, public_id, expires, token_hash)}"


def read_code(code: str) -> ResumeCode | None:
    """The parts of ``code``, or ``None`` when it is not shaped like one."""
    parts = code.split(".")
    if len(parts) != 3 or not parts[1].isdigit() or len(parts[1]) > 12 or not parts[0] or not parts[2]:
        return None
    return ResumeCode(parts[0], int(parts[1]), parts[2])


def verify(secret: bytes, code: ResumeCode, token_hash: str, now: float) -> bool:
    """Whether ``code`` was made for the participant's current token hash and has not expired."""
    expected = _signature(secret, code.public_id, code.expires, token_hash)
    return now <= code.expires and hmac.compare_digest(expected, code.signature)


def resume_path(study_id: str, code: str) -> str:
    """The link's path: the study's landing page with the code in the fragment."""
    return f"/?study={study_id}#{RESUME_FRAGMENT}={code}"
