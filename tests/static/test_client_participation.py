"""A participant who does not take part, in real Chromium: under the paper's clock an idle cook is
nudged ("Choose your next task"), the round ends at its wall-clock limit and says so, and the end page shows the
screen-out code with the participant's true reason (the rule they did not meet), never the completion code. The round's wall clock is moved by hand."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from steakhouse_browser import start_first_round
from steakhouse_study_server import ADMIN_TOKEN, REPO, StudyServer
from steakhouse_testing import ManualClock, ThreadServer, write_study

pytestmark = pytest.mark.browser

LIMIT_S = 30.0


@pytest.fixture(scope="module")
def waiting_server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[StudyServer, ManualClock]]:
    from server.app import create_app
    from server.settings import Settings

    folder: Path = tmp_path_factory.mktemp("participation")
    study = write_study(folder, "waiting", kitchens=["none_3"], robots=["stay"],
                        timing={"mode": "wait_for_participant", "tick_rate_hz": 10, "max_round_seconds": LIMIT_S,
                                "idle_nudge_seconds": 5},
                        recruiting={"completion_code": "PAID-1", "screen_out_code": "NOT-PAID-2"})
    settings = Settings(database_url=f"sqlite:///{folder / 'store.sqlite3'}", study_files=(study,), robot_workers=0,
                        admin_token=ADMIN_TOKEN, flush_interval_s=0.1, static_dir=REPO / "static",
                        join_rate_per_minute=0)
    clock = ManualClock()
    with ThreadServer(create_app(settings, clock=clock)) as thread:
        server = StudyServer(thread)
        try:
            yield server, clock
        finally:
            server.admin.close()


def test_an_idle_participant_is_nudged_timed_out_and_screened_out(waiting_server, new_page):
    server, clock = waiting_server
    page, _ = new_page()
    start_first_round(page, server.link("waiting", PROLIFIC_PID="pid-idle"))
    clock.advance(5.0)
    page.wait_for_function("() => document.querySelector('#task-note') && !document.querySelector('#task-note')"
                           ".hidden && document.querySelector('#task-note').textContent.includes('Choose your next')")
    clock.advance(LIMIT_S)
    page.wait_for_selector("#round-summary")
    assert "time limit" in page.inner_text("#summary-text")
    page.click("#continue")
    page.wait_for_selector("#finish[data-kind='screen_out']")
    text: Any = page.inner_text("#finish-text")
    assert text.startswith("In round 1 you did not choose a task or press a key, so that round cannot count.")
    assert page.inner_text("#completion-code") == "NOT-PAID-2"
    assert "PAID-1" not in page.inner_text("body").replace("NOT-PAID-2", "")
    [row] = [p for p in server.get("/api/admin/participants") if p["recruiting"].get("PROLIFIC_PID") == "pid-idle"]
    assert (row["status"], row["screen_out_reason"]) == ("screened_out", "low_engagement")
