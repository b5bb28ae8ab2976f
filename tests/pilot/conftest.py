"""Fixtures of the pilot tests: the paper study loaded as the pilot loads it, and the offline-trial helper."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

from study_config import STUDY_DIR
from study_config.catalog import LoadedStudy, load_one


@pytest.fixture(scope="session")
def paper() -> LoadedStudy:
    return load_one(STUDY_DIR / "paper_study.yaml")
