"""The repository's nginx configuration (``server/deploy/nginx.conf``) run for a test: only its addresses are
rendered (listen ports on 127.0.0.1, the upstream servers, a self-signed certificate) and a temporary prefix
added; nginx runs in the foreground as a child process and is stopped by its pid.

Also: a participant that speaks to the server *through* the proxy like the browser does — REST over HTTPS,
the websocket over WSS with the token offered as the subprotocol ``token.<token>`` (the header the proxy
hashes on), and the browser's reconnect back-off (``static/js/game/connection.js``).
"""

from __future__ import annotations

import contextlib
import functools
import os
import re
import shutil
import signal
import ssl
import subprocess
import tempfile
import time
from pathlib import Path
from typing import Any

import httpx
from steakhouse_testing import REPO, Player, Socket, free_port
from websockets.asyncio.client import connect
from websockets.typing import Subprotocol

CONFIG = REPO / "server" / "deploy" / "nginx.conf"
UPSTREAM_LINE = re.compile(r"^([ \t]*)server app\d+:8000( [^;]*)?;\n", re.MULTILINE)
BACKOFF_MIN_S, BACKOFF_MAX_S = 0.25, 8.0


def nginx_binary() -> str | None:
    return shutil.which("nginx") or next((p for p in ("/usr/sbin/nginx",) if os.access(p, os.X_OK)), None)


def render(text: str, *, backends: list[str], http_port: int, https_port: int, folder: Path,
           play: list[str] | None = None) -> str:
    """``text`` (the repository's file) with its addresses replaced (``play``: other servers for the websocket
    upstream, the first block); raises if the file no longer has the shape this test relies on (then the test and
    the file must change together)."""
    blocks_seen = 0

    def upstream(block: re.Match[str]) -> str:
        nonlocal blocks_seen
        first = UPSTREAM_LINE.match(block.group(0))
        assert first is not None
        servers = play if play is not None and blocks_seen == 0 else backends
        blocks_seen += 1
        return "".join(f"{first.group(1)}server {b}{first.group(2) or ''};\n" for b in servers)

    rendered, blocks = re.subn(r"(?:^[ \t]*server app\d+:8000[^;]*;\n)+", upstream, text, flags=re.MULTILINE)
    replacements = [("listen 80;", f"listen 127.0.0.1:{http_port};"),
                    ("listen 443 ssl;", f"listen 127.0.0.1:{https_port} ssl;"),
                    ("/etc/nginx/tls/", f"{folder}/")]
    for old, new in replacements:
        if old not in rendered:
            raise ValueError(f"{CONFIG}: expected {old!r}")
        rendered = rendered.replace(old, new)
    if blocks != 2:
        raise ValueError(f"{CONFIG}: expected two upstream blocks of `server appN:8000` lines, found {blocks}")
    temp = "".join(f"    {kind}_temp_path {folder}/{kind};\n"
                   for kind in ("client_body", "proxy", "fastcgi", "uwsgi", "scgi"))
    rendered = rendered.replace("http {\n", "http {\n" + temp, 1)
    return f"pid {folder}/nginx.pid;\nerror_log {folder}/error.log notice;\n" + rendered


def self_signed(folder: Path) -> None:
    subprocess.run(["openssl", "req", "-x509", "-newkey", "rsa:2048", "-nodes", "-days", "1", "-subj", "/CN=localhost",
                    "-keyout", str(folder / "study.key"), "-out", str(folder / "study.crt")],
                   check=True, capture_output=True)


class NginxProxy:
    """nginx with the repository's configuration in front of ``backends`` (``host:port``)."""

    def __init__(self, backends: list[str]) -> None:
        self.backends = backends
        self.http_port, self.https_port = free_port(), free_port()
        self.url = f"https://127.0.0.1:{self.https_port}"
        self.process: subprocess.Popen[bytes] | None = None
        self.folder = Path(tempfile.mkdtemp(prefix="steakhouse-nginx-"))
        self.folder.chmod(0o755)  # nginx's workers (user nobody when started as root) use the temp paths

    def start(self) -> NginxProxy:
        binary = nginx_binary()
        if binary is None:
            raise RuntimeError("nginx is not installed (tests/tools/ensure_nginx.sh installs it)")
        self_signed(self.folder)
        conf = self.folder / "nginx.conf"
        conf.write_text(render(CONFIG.read_text(encoding="utf-8"), backends=self.backends,
                               http_port=self.http_port, https_port=self.https_port, folder=self.folder))
        test = subprocess.run([binary, "-t", "-p", str(self.folder), "-e", str(self.folder / "error.log"),
                               "-c", str(conf)], capture_output=True, text=True)
        if test.returncode != 0:
            raise RuntimeError(f"nginx rejects the rendered configuration: {test.stderr}")
        self.process = subprocess.Popen([binary, "-p", str(self.folder), "-e", str(self.folder / "error.log"),
                                         "-c", str(conf), "-g", "daemon off;"],
                                        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        deadline = time.monotonic() + 20
        with httpx.Client(timeout=1, verify=client_tls()) as http:
            while time.monotonic() < deadline:
                if self.process.poll() is not None:
                    raise RuntimeError(f"nginx exited with {self.process.returncode}: {self.error_log()}")
                with contextlib.suppress(httpx.HTTPError):
                    http.get(f"http://127.0.0.1:{self.http_port}/")
                    return self
                time.sleep(0.05)
        raise RuntimeError("nginx did not start listening")

    def reload(self, play: list[str] | None = None) -> None:
        """Reload nginx with ``play`` as the websocket upstream's servers (``None``: all backends again), as an
        operator changing the set does. nginx keeps the websockets already open (its old workers serve them until
        they close); new ones are hashed over the new set. Returns once the new workers answer."""
        assert self.process is not None
        conf = self.folder / "nginx.conf"
        conf.write_text(render(CONFIG.read_text(encoding="utf-8"), backends=self.backends, play=play,
                               http_port=self.http_port, https_port=self.https_port, folder=self.folder))
        def shutting(pid: int) -> bool:
            return f"{pid}#{pid}: gracefully shutting down" in self._log()

        accepting = {pid for pid in self._workers() if not shutting(pid)}
        self.process.send_signal(signal.SIGHUP)
        deadline = time.monotonic() + 20
        # Each accepting worker logs this once it stopped accepting connections (it keeps serving those it has).
        while time.monotonic() < deadline:
            if all(shutting(pid) for pid in accepting):
                return
            time.sleep(0.05)
        raise RuntimeError(f"nginx did not reload: {self.error_log()}")

    def _workers(self) -> set[int]:
        assert self.process is not None
        children = Path(f"/proc/{self.process.pid}/task/{self.process.pid}/children")
        return {int(pid) for pid in children.read_text().split()} if children.exists() else set()

    def _log(self) -> str:
        log = self.folder / "error.log"
        return log.read_text(errors="replace") if log.exists() else ""

    def error_log(self) -> str:
        log = self.folder / "error.log"
        return log.read_text(errors="replace")[-3000:] if log.exists() else ""

    def stop(self) -> None:
        if self.process is not None and self.process.poll() is None:
            self.process.send_signal(signal.SIGTERM)
            try:
                self.process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait(timeout=10)
        shutil.rmtree(self.folder, ignore_errors=True)


@functools.cache
def client_tls() -> ssl.SSLContext:
    """Trust the test's self-signed certificate. One context for every client: building one loads the
    system's CA bundle (tens of ms on a busy machine), which would otherwise delay reconnects measured here."""
    context = ssl.SSLContext(ssl.PROTOCOL_TLS_CLIENT)
    context.check_hostname = False
    context.verify_mode = ssl.CERT_NONE
    return context


class ProxiedPlayer(Player):  # type: ignore[misc]  # Player: imported by its sys.path name, unresolved (Any)
    """A participant reaching the servers only through the proxy, as a browser does."""

    def __init__(self, base_url: str) -> None:
        self.base, self.token = base_url, ""
        self.http = httpx.AsyncClient(base_url=base_url, timeout=30, verify=client_tls())

    async def socket(self) -> Socket:
        url = self.base.replace("https", "wss", 1) + "/ws/play"
        protocols = [Subprotocol("steakhouse.v1"), Subprotocol(f"token.{self.token}")]
        return Socket(await connect(url, ssl=client_tls(), subprotocols=protocols, max_size=1 << 22,
                                    max_queue=None))


def backoff_s(attempt: int) -> float:
    """The browser's reconnect delay before attempt ``attempt`` (0-based), without its ±20 % jitter."""
    return min(BACKOFF_MAX_S, BACKOFF_MIN_S * 2.0 ** max(0, attempt))


def trial_processes(events: list[Any]) -> dict[int, list[str]]:
    """Trial id → the server processes that started or resumed it, in order (from ``trial_start`` /
    ``resume`` events)."""
    out: dict[int, list[str]] = {}
    for event in events:
        if event.kind in ("trial_start", "resume") and event.trial_id is not None:
            out.setdefault(event.trial_id, []).append(event.payload.get("process"))
    return out
