"""The packages type-check with mypy (settings in pyproject.toml): typed state, messages and configs are a
habit of this codebase, and the checker finds what a test run does not reach (it found a shadowed variable
and a str/bool mix-up in the KB's streaks)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]


@pytest.mark.slow  # mypy over every package: over a minute without a cache (a fresh clone)
@pytest.mark.timeout(600)
def test_mypy_reports_no_errors() -> None:
    done = subprocess.run([sys.executable, "-m", "mypy", "--no-error-summary"], cwd=REPO, capture_output=True,
                          text=True, timeout=600, check=False)
    assert done.returncode == 0, done.stdout[-4000:] + done.stderr[-2000:]
