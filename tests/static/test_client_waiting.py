"""The waiting page in real Chromium: with one live-trial slot taken, a participant who starts their round is
told when it starts and their place in line (nothing about the round's condition), then plays once the slot
frees; one who waits past the limit gets the screen-out code and why (docs/protocol.md, "Waiting for a slot")."""

from __future__ import annotations

import asyncio
import threading
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import yaml
from steakhouse_browser import wait_drawn
from steakhouse_testing import Player, ThreadServer, play_to_end

pytestmark = pytest.mark.browser

STUDY = {
    "id": "busy", "title": "Busy server test study", "kitchens": ["none_3"], "robots": ["stay"],
    "factors": ["robot"], "timing": {"tick_rate_hz": 20}, "world": {"orders": 1, "horizon": 1200, "kb_delay": 1},
    "recruiting": {"screen_out_code": "BUSY-1"},
}
CONDITION_WORDS = ("stay", "none_3", "busy server test study")


def serve(tmp_path_factory: pytest.TempPathFactory, **settings: Any) -> Iterator[ThreadServer]:
    from pydantic import SecretStr

    from server.app import create_app
    from server.settings import Settings

    folder = tmp_path_factory.mktemp("busy")
    study = folder / "busy.yaml"
    study.write_text(yaml.safe_dump(STUDY), encoding="utf-8")
    config = Settings(database_url=f"sqlite:///{folder / 'store.sqlite3'}", study_files=(study,),
                      robot_workers=0, admin_token=SecretStr("busy-admin"), flush_interval_s=0.1,
                      static_dir=Path(__file__).resolve().parents[2] / "static", join_rate_per_minute=0,
                      max_live_trials=1, **settings)
    with ThreadServer(create_app(config)) as thread:
        yield thread


@pytest.fixture(scope="module")
def busy_server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[ThreadServer]:
    yield from serve(tmp_path_factory)


@pytest.fixture(scope="module")
def impatient_server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[ThreadServer]:
    """Participants may wait 3 s for a slot."""
    yield from serve(tmp_path_factory, admission_max_wait_s=3.0)


def test_a_participant_waits_for_a_free_slot_then_plays(busy_server, new_page):
    holder_ready, release = threading.Event(), threading.Event()
    held: list[int] = []

    async def hold_the_slot() -> None:
        """Another participant's round takes the one slot; once released it is played to its end."""
        player = Player(busy_server.url)
        await player.ready("busy")
        sock = await player.socket()
        held.append((await sock.recv())["trial"]["id"])
        holder_ready.set()
        await asyncio.to_thread(release.wait, 60)
        await play_to_end(sock)
        await sock.close()
        await player.close()

    holder = threading.Thread(target=lambda: asyncio.run(hold_the_slot()), daemon=True)
    holder.start()
    assert holder_ready.wait(30)
    registry = busy_server.services.registry
    page, _ = new_page()
    page.goto(f"{busy_server.url}/?study=busy")
    for selector in ("#consent-agree", "#instructions-done", "#start-round"):
        page.wait_for_selector(selector)
        page.click(selector)
    page.wait_for_function("() => document.querySelector('#stage-cover').textContent.includes('in line')"
                           " || document.querySelector('#stage-cover').textContent.includes('You are next')")
    cover = page.inner_text("#stage-cover")
    assert "your round starts in about" in cover and "keep this tab open" in cover and "You are next" in cover
    assert page.inner_text("#link-status") == "Waiting for your round"
    text = page.inner_text("body").lower()
    assert not any(word in text for word in CONDITION_WORDS), text
    assert registry.lobby.admission.waiting == 1

    release.set()
    drawn = wait_drawn(page)
    assert drawn.trial != held[0]
    assert page.locator("#stage-cover").is_hidden()
    holder.join(30)


def test_a_participant_who_waited_too_long_gets_the_screen_out_code(impatient_server, new_page):
    holding, release = threading.Event(), threading.Event()

    async def take_the_slot() -> None:
        player = Player(impatient_server.url)
        await player.ready("busy")
        sock = await player.socket()
        await sock.recv()
        holding.set()
        await asyncio.to_thread(release.wait, 60)
        await sock.close()
        await player.close()

    holder = threading.Thread(target=lambda: asyncio.run(take_the_slot()), daemon=True)
    holder.start()
    assert holding.wait(30)
    try:
        page, _ = new_page()
        page.goto(f"{impatient_server.url}/?study=busy")
        for selector in ("#consent-agree", "#instructions-done", "#start-round"):
            page.wait_for_selector(selector)
            page.click(selector)
        page.wait_for_selector("#completion-code")
        assert page.inner_text("#completion-code") == "BUSY-1"
        assert "too busy to start your round" in page.inner_text("#finish-text")
    finally:
        release.set()
        holder.join(30)
