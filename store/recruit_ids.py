"""One person, one recruiting id: the key a recruiting id (e.g. a Prolific id) is compared by, so that look-alikes
of an id are the same participant (docs/protocol.md §1).

``recruit_key(raw)``:

1. Unicode NFKC (full-width ``ＡＢＣ`` is ``ABC``, ``ﬁ`` is ``fi``);
2. combining marks removed after canonical decomposition (``abć`` and ``abc`` + U+0301 are ``abc``: no recruiting
   platform's ids carry diacritics);
3. the confusable skeleton of Unicode Technical Standard #39 with case folded, from ``disarm``'s
   ``skeleton_key`` (pinned in ``pyproject.toml``: a minor release may change keys): it removes format and other
   invisible characters (zero-width space and joiner, soft hyphen, bidi controls), maps look-alikes from other
   scripts to their prototype (Cyrillic ``а`` is Latin ``a``), and puts ``0``/``O``/``o`` and ``1``/``l``/``I``
   in one class each (``digit_policy="tr39"``, what an identifier skeleton wants);
4. marks removed again, surrounding space trimmed, at most 200 characters.

An id whose key is empty (blank, or made only of invisible characters) is no id. The store keeps the id as given
(``participants.recruit_id``, shown to the experimenter and exported) beside its key
(``participants.recruit_key``, unique per study).
"""

from __future__ import annotations

import unicodedata

from disarm import skeleton_key

MAX_LENGTH = 200
_MARKS = frozenset({"Mn", "Me"})


def _without_marks(text: str) -> str:
    return "".join(c for c in unicodedata.normalize("NFD", text) if unicodedata.category(c) not in _MARKS)


def recruit_key(raw: str | None) -> str | None:
    """The key ``raw`` is compared by (see the module's docstring); ``None`` when it is no id."""
    if raw is None:
        return None
    key = _without_marks(skeleton_key(_without_marks(unicodedata.normalize("NFKC", raw)), digit_policy="tr39"))
    return key.strip()[:MAX_LENGTH] or None
