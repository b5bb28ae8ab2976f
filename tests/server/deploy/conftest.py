"""Fixtures of the deployment tests: nginx with the repository's configuration (``server/deploy/nginx.conf``)
in front of ``steakhouse serve`` processes. nginx missing: skipped with the reason, or failed when
``CI=true`` (``tests/tools/ensure_nginx.sh``, run by ``make test``, installs it)."""

from __future__ import annotations

import os
import sys
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

from nginx_proxy import NginxProxy, nginx_binary


@pytest.fixture
def nginx() -> Iterator[Callable[[list[str]], NginxProxy]]:
    """``nginx(["127.0.0.1:8001", …])``: a started proxy in front of those servers, stopped after the test."""
    if nginx_binary() is None:
        reason = "nginx is not installed (tests/tools/ensure_nginx.sh installs Debian's)"
        if os.environ.get("CI", "").lower() == "true":
            pytest.fail(f"CI requires nginx for the deployment tests: {reason}")
        pytest.skip(reason)
    started: list[NginxProxy] = []

    def start(backends: list[str]) -> NginxProxy:
        proxy = NginxProxy(backends)
        started.append(proxy)
        return proxy.start()

    yield start
    for proxy in started:
        proxy.stop()
