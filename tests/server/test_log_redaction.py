"""Participant tokens stay out of the server's log: ``steakhouse serve`` redacts ``token=`` query values in
uvicorn's websocket and access log lines (the websocket takes ``?token=``; browsers cannot set headers)."""

from __future__ import annotations

import asyncio
import logging

import httpx
from steakhouse_testing import Player, ProcessServer
from uvicorn.logging import AccessFormatter

from server.commands.serve import RedactTokens, install_redaction, redact


def test_redact_replaces_only_token_values():
    assert redact("/ws/play?token=abc-DEF_123") == "/ws/play?token=[redacted]"
    assert redact("/x?a=1&token=s3cret&b=2") == "/x?a=1&token=[redacted]&b=2"
    assert redact("/x?tokens=keep&mytoken=keep") == "/x?tokens=keep&mytoken=keep"
    assert redact("no query at all") == "no query at all"


def test_the_filter_keeps_uvicorns_access_record_shape():
    record = logging.LogRecord("uvicorn.access", logging.INFO, __file__, 1, '%s - "%s %s HTTP/%s" %d',
                               ("127.0.0.1:5000", "GET", "/api/session?token=s3cret", "1.1", 200), None)
    assert RedactTokens().filter(record) is True
    line = AccessFormatter("%(client_addr)s - \"%(request_line)s\" %(status_code)s", use_colors=False).format(record)
    assert line == '127.0.0.1:5000 - "GET /api/session?token=[redacted] HTTP/1.1" 200 OK'


def test_install_is_idempotent():
    install_redaction(("steakhouse.test.redaction",))
    install_redaction(("steakhouse.test.redaction",))
    filters = logging.getLogger("steakhouse.test.redaction").filters
    assert sum(isinstance(f, RedactTokens) for f in filters) == 1


def test_a_served_websocket_and_a_query_token_leave_no_token_in_the_log(study_file, tmp_path):
    log = tmp_path / "server.log"
    server = ProcessServer(study=study_file(), database_url=f"sqlite:///{tmp_path / 'store.sqlite3'}", workers=0,
                           log=log, log_level="info")
    server.start()
    try:
        async def scenario() -> str:
            player = Player(server.url)
            await player.ready()
            sock = await player.socket()
            assert (await sock.recv())["type"] == "hello"
            await sock.close()
            await player.close()
            token: str = player.token
            return token

        token = asyncio.run(scenario())
        assert httpx.get(f"{server.url}/api/session", params={"token": token}).status_code == 200
    finally:
        server.stop()
    text = log.read_text(encoding="utf-8")
    assert '"WebSocket /ws/play?token=[redacted]" [accepted]' in text
    assert "GET /api/session?token=[redacted] HTTP/1.1" in text
    assert token not in text
