"""The end page of a real participant never shows a placeholder code.

A study whose ``recruiting.completion_code`` (or ``screen_out_code``) is still the placeholder shipped with the
example (``REPLACE-WITH-YOUR-…``, :data:`study_config.study.warnings.PLACEHOLDER_PREFIX`) has not been set up for
payment: a real participant who reached its end gets no code and no redirect, and their end page says so and
asks them to contact the researcher (``not_set_up: true``). Test runs and pilot participants still see the
placeholder, so an experimenter trying the study sees where the code will appear; ``steakhouse serve`` warns
at start (docs/deploy.md, "Before recruiting").
"""

from __future__ import annotations

from typing import Any

from store.tables import ParticipantRow
from study_config.study.warnings import PLACEHOLDER_PREFIX


def is_placeholder(code: str | None) -> bool:
    return bool(code and code.startswith(PLACEHOLDER_PREFIX))


def shown_to(row: ParticipantRow, completion: dict[str, Any]) -> dict[str, Any]:
    """``completion`` (:func:`server.flow.service.completion`) as ``row``'s end page may show it."""
    if row.test_run or row.pilot or not is_placeholder(completion.get("code")):
        return completion
    return {**completion, "code": None, "redirect_url": None, "not_set_up": True}
