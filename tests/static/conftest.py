"""Fixtures of the browser tests: Debian's Chromium driven by Playwright, and a real study server (uvicorn
on 127.0.0.1, a free port, stopped after the module) serving ``static/`` and the study files in
``tests/static/studies/``.

Without ``chromium`` on the PATH the browser tests are skipped with the reason, except when ``CI=true``:
then they fail. Every page records console errors and uncaught exceptions; a test fails if any occurred.
"""

from __future__ import annotations

import os
import shutil
import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

HERE = Path(__file__).resolve().parent
STUDIES = HERE / "studies"
CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
                 "--disable-sync", "--no-first-run"]
WEBGL_ARGS = ["--no-sandbox", "--use-gl=angle", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
              "--ignore-gpu-blocklist", "--disable-background-networking", "--disable-component-update",
              "--disable-sync", "--no-first-run"]
"""Chromium with software WebGL (SwiftShader through ANGLE), for the first-person view."""

sys.path.insert(0, str(HERE.parent / "server"))
sys.path.insert(0, str(HERE))

from steakhouse_browser import RECRUIT_SITE, screenshot  # noqa: E402, F401  (screenshot re-exported for old imports)
from steakhouse_study_server import ADMIN_TOKEN, REPO, StudyServer  # noqa: E402
from steakhouse_testing import ThreadServer  # noqa: E402


def chromium_or_skip() -> str:
    path = shutil.which("chromium")
    if path is None:
        reason = "Debian's chromium is not installed (run `make browser` or tests/tools/ensure_chromium.sh)"
        if os.environ.get("CI", "").lower() == "true":
            pytest.fail(f"CI requires the browser tests: {reason}")
        pytest.skip(reason)
    return path


@pytest.fixture(scope="session")
def playwright_driver() -> Iterator[Any]:
    """One Playwright driver per test process (each pytest-xdist worker), shared by its browsers."""
    chromium_or_skip()
    from playwright.sync_api import sync_playwright

    with sync_playwright() as playwright:
        yield playwright


def _launch(playwright: Any, args: list[str]) -> Iterator[Any]:
    launched = playwright.chromium.launch(executable_path=chromium_or_skip(), headless=True, args=args)
    try:
        yield launched
    finally:
        launched.close()


# One browser per worker for the whole session: every page the tests open is in a fresh context (``new_page``,
# ``admin_page``: its own cookies, storage and cache, closed after the test), so nothing carries over between
# tests, and Chromium starts once per worker instead of once per module.
@pytest.fixture(scope="session")
def browser(playwright_driver: Any) -> Iterator[Any]:
    yield from _launch(playwright_driver, CHROMIUM_ARGS)


@pytest.fixture(scope="session")
def gl_browser(playwright_driver: Any) -> Iterator[Any]:
    """Chromium with software WebGL (``WEBGL_ARGS``)."""
    yield from _launch(playwright_driver, WEBGL_ARGS)


@pytest.fixture(scope="module")
def study_server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[StudyServer]:
    from pydantic import SecretStr

    from server.app import create_app
    from server.settings import Settings

    folder = tmp_path_factory.mktemp("browser-store")
    settings = Settings(database_url=f"sqlite:///{folder / 'store.sqlite3'}",
                        study_files=tuple(sorted(STUDIES.glob("*.yaml"))), robot_workers=0,
                        admin_token=SecretStr(ADMIN_TOKEN), flush_interval_s=0.1, static_dir=REPO / "static",
                        join_rate_per_minute=0)
    with ThreadServer(create_app(settings)) as thread:
        server = StudyServer(thread)
        try:
            yield server
        finally:
            server.admin.close()


class PageProblems(list[str]):
    """Console errors and uncaught exceptions of one page."""


@pytest.fixture
def new_page(browser: Any) -> Iterator[Callable[..., tuple[Any, PageProblems]]]:
    """``new_page(viewport=(1280, 720), scale=1, **context)``: a page in a fresh browser context (a new
    participant; ``context``: more Playwright context options, e.g. ``is_mobile``, ``has_touch``) with the
    recruiting site stubbed; fails the test if the page logged a console error."""
    yield from _pages(browser)


@pytest.fixture
def new_gl_page(gl_browser: Any) -> Iterator[Callable[..., tuple[Any, PageProblems]]]:
    """``new_page`` in Chromium with software WebGL."""
    yield from _pages(gl_browser)


def _pages(browser: Any) -> Iterator[Callable[..., tuple[Any, PageProblems]]]:
    contexts: list[tuple[Any, PageProblems]] = []

    def make(viewport: tuple[int, int] = (1280, 720), scale: float = 1, **options: Any) -> tuple[Any, PageProblems]:
        context = browser.new_context(viewport={"width": viewport[0], "height": viewport[1]},
                                      device_scale_factor=scale, **options)
        context.route(f"{RECRUIT_SITE}**", lambda route: route.fulfill(
            status=200, content_type="text/html", body="<!doctype html><title>Recruiting site</title><p>Welcome back"))
        page = context.new_page()
        problems = PageProblems()
        page.on("console", lambda msg: problems.append(f"console.{msg.type}: {msg.text}")
                if msg.type == "error" else None)
        page.on("pageerror", lambda exc: problems.append(f"uncaught: {exc}"))
        contexts.append((context, problems))
        return page, problems

    yield make
    failures = [p for _, problems in contexts for p in problems]
    for context, _ in contexts:
        context.close()
    assert failures == [], failures


@pytest.fixture(scope="module")
def pure_module_page(study_server: StudyServer, browser: Any) -> Iterator[Any]:
    """``module_page`` shared by the tests of one module, for tests that only call the client's pure functions
    (nothing they do changes what the next test reads): one page load for all of them. Console errors fail the
    module's last test, as ``new_page``'s fail their test."""
    pages = _pages(browser)
    page, _ = next(pages)()
    page.goto(f"{study_server.url}/data/example_view.json")
    yield page
    next(pages, None)  # closes the context and asserts that the page logged no error


@pytest.fixture
def module_page(study_server: StudyServer, new_page: Callable[..., tuple[Any, PageProblems]]) -> Any:
    """A page on the study server (a static file, no study page) for importing the client's modules one by one."""
    page, _ = new_page()
    page.goto(f"{study_server.url}/data/example_view.json")
    return page
