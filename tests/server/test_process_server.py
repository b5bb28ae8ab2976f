"""The test harness's server in a child process (``steakhouse_testing.ProcessServer``): a test talks to the server it
started, never to another test's server that took its port first (a loaded run connected a participant to another
test's server and was refused as unauthorized)."""

from __future__ import annotations

import os
import socket

import httpx
import pytest
from steakhouse_testing import ProcessServer, listening_pids

pytestmark = pytest.mark.store_agnostic


def test_a_server_whose_port_was_taken_starts_on_another_and_is_the_one_answering(db_url, study_file):
    with socket.socket() as squatter:
        squatter.bind(("127.0.0.1", 0))
        squatter.listen()
        taken = squatter.getsockname()[1]
        assert listening_pids(taken) == {os.getpid()}
        server = ProcessServer(study=study_file(), database_url=db_url, workers=0)
        server.port = taken  # as if another process bound the port between free_port() and the launch
        try:
            server.start()
            assert server.port != taken
            assert server.process is not None and listening_pids(server.port) == {server.process.pid}
            assert httpx.get(server.url + "/healthz", timeout=10).json()["status"] == "ok"
        finally:
            server.kill()
