"""Phone → laptop: a session the device check refused on its first device continues on another one only with the
secret its first device shows (docs/protocol.md §1, "Phone first, then a laptop").

While a session is claimable (its device was refused and it has not moved past its first step), its browser's
session view carries a hand-off code (``handoff.code``, e.g. ``K7QPM-4XWZA``) and the page shows it with a link
that carries it (``…#handoff=<code>``). Another browser joining with the same recruiting id continues the session
only with that code; with the id alone it is refused (``409 handoff_code_required``), with a wrong code too
(``409 handoff_code_wrong``, stored as a ``handoff_refused`` event). After :data:`MAX_WRONG` wrong codes the session
can no longer be handed off (``409 handoff_locked``; the researcher's resume link still moves it).

The code is an HMAC of the participant's public id and current token hash, keyed by a secret derived from the admin
token: nothing is stored, every server process agrees, and it stops working once the session is handed off (the
token changes). 50 bits: guessing one among :data:`MAX_WRONG` tries is hopeless.
"""

from __future__ import annotations

import base64
import hashlib
import hmac
import re

HANDOFF_FRAGMENT = "handoff"
MAX_WRONG = 10
"""Wrong hand-off codes a session takes before it can no longer be handed off."""
_CONTEXT = b"steakhouse.handoff.v1\0"
_LENGTH = 10


def handoff_key(admin_token: str) -> bytes:
    return hashlib.sha256(_CONTEXT + admin_token.encode("utf-8")).digest()


def handoff_code(key: bytes, public_id: str, token_hash: str) -> str:
    """The session's hand-off code, as shown: two groups of five letters and digits (base32)."""
    mac = hmac.new(key, f"{public_id}.{token_hash}".encode(), hashlib.sha256).digest()
    code = base64.b32encode(mac).decode()[:_LENGTH]
    return f"{code[:5]}-{code[5:]}"


def _typed(code: str) -> str:
    """A typed code as compared: spaces and dashes dropped, upper case, 0 read as O and 1 as I (base32 has
    neither digit)."""
    return re.sub(r"[\s\-]", "", code).upper().replace("0", "O").replace("1", "I")


def matches(key: bytes, typed: str, public_id: str, token_hash: str) -> bool:
    return hmac.compare_digest(_typed(typed).encode(), _typed(handoff_code(key, public_id, token_hash)).encode())
