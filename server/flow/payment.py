"""The end page of a real participant never shows a placeholder code, and a test run never shows a real one.

A study whose ``recruiting.completion_code`` (or ``screen_out_code``) is still the placeholder shipped with the
example (``REPLACE-WITH-YOUR-…``, :data:`study_config.study.warnings.PLACEHOLDER_PREFIX`) has not been set up for
payment: a real participant who reached its end gets no code and no redirect, and their end page says so and
asks them to contact the researcher (``not_set_up: true``). Test runs and pilot participants still see the
placeholder, so an experimenter trying the study sees where the code will appear; ``steakhouse serve`` warns
at start (docs/deploy.md, "Before recruiting").

A test run (an admin-signed test link, or a participant the admin marked; ``server.admin.test_links``) is shown
:data:`TEST_RUN_CODE` in place of any code, and no redirect: the study's real completion code is for paid
participants only, and a test link that leaked must not hand it out.
"""

from __future__ import annotations

from typing import Any

from store.tables import ParticipantRow
from study_config.study.warnings import PLACEHOLDER_PREFIX

TEST_RUN_CODE = "TEST-RUN"
"""What a test run's end page shows in place of the study's codes."""


def is_placeholder(code: str | None) -> bool:
    return bool(code and code.startswith(PLACEHOLDER_PREFIX))


def shown_to(row: ParticipantRow, completion: dict[str, Any]) -> dict[str, Any]:
    """``completion`` (:func:`server.flow.service.completion`) as ``row``'s end page may show it."""
    if row.test_run:
        return {**completion, "code": TEST_RUN_CODE, "redirect_url": None, "test_run": True}
    if row.pilot or not is_placeholder(completion.get("code")):
        return completion
    return {**completion, "code": None, "redirect_url": None, "not_set_up": True}
