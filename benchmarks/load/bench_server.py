"""The server under test: ``steakhouse serve`` in a child process on 127.0.0.1 (a free port), on a store of
its own (a temporary SQLite file, or a PostgreSQL database created for the run and dropped after it), and a
sampler of its CPU time and memory (the server process plus its robot workers; ``psutil`` when installed,
else ``/proc``).
"""

from __future__ import annotations

import contextlib
import os
import secrets
import signal
import socket
import subprocess
import sys
import threading
import time
import uuid
from collections.abc import Iterator
from pathlib import Path
from typing import Any, BinaryIO

import httpx

REPO = Path(__file__).resolve().parents[2]
DEFAULT_POSTGRES = "postgresql+psycopg://postgres@127.0.0.1:5432/test"


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


@contextlib.contextmanager
def temporary_database(kind: str, folder: Path, postgres_url: str = DEFAULT_POSTGRES) -> Iterator[str]:
    """A store URL for an empty database: ``sqlite`` (a file in ``folder``) or ``postgresql`` (a database
    created on the server named by ``postgres_url`` and dropped, connections and all, afterwards)."""
    if kind == "sqlite":
        yield f"sqlite:///{folder / 'load.sqlite3'}"
        return
    from sqlalchemy import create_engine, text
    from sqlalchemy.engine import make_url

    admin = create_engine(postgres_url, isolation_level="AUTOCOMMIT", connect_args={"connect_timeout": 5})
    name = f"steakhouse_load_{uuid.uuid4().hex[:12]}"
    with admin.connect() as conn:
        conn.execute(text(f'CREATE DATABASE "{name}"'))
    try:
        yield make_url(postgres_url).set(database=name).render_as_string(hide_password=False)
    finally:
        with admin.connect() as conn:
            conn.execute(text(f'DROP DATABASE IF EXISTS "{name}" WITH (FORCE)'))
        admin.dispose()


class BenchServer:
    """``steakhouse serve`` for one benchmark run; :meth:`stop` ends it with SIGTERM (a clean shutdown that
    flushes the store), SIGKILL if it hangs."""

    def __init__(self, *, study: Path, database_url: str, workers: int, log: Path,
                 env: dict[str, str] | None = None) -> None:
        self.port = free_port()
        self.url = f"http://127.0.0.1:{self.port}"
        self.admin_token = secrets.token_urlsafe(16)
        self.args = [sys.executable, "-m", "server.cli", "serve", "--port", str(self.port), "--study", str(study),
                     "--database-url", database_url, "--workers", str(workers), "--log-level", "warning"]
        # Every simulated participant comes from 127.0.0.1: the per-address join limit would measure itself.
        self.env = {**os.environ, "STEAKHOUSE_ADMIN_TOKEN": self.admin_token,
                    "STEAKHOUSE_JOIN_RATE_PER_MINUTE": "0", "PYTHONPATH": str(REPO), **(env or {})}
        self.log = log
        self.process: subprocess.Popen[bytes] | None = None
        self._out: BinaryIO | None = None

    def __enter__(self) -> BenchServer:
        self._out = open(self.log, "ab")
        self.process = subprocess.Popen(self.args, cwd=REPO, env=self.env, stdout=self._out, stderr=self._out)
        deadline = time.monotonic() + 90
        # One client for the polls (httpx.get builds a client and its TLS context each time: CPU the server
        # starting beside it would lose).
        with httpx.Client(timeout=1) as http:
            while time.monotonic() < deadline:
                if self.process.poll() is not None:
                    raise RuntimeError(f"the server exited with {self.process.returncode}; see {self.log}")
                with contextlib.suppress(httpx.HTTPError):
                    if http.get(self.url + "/healthz").status_code == 200:
                        return self
                time.sleep(0.1)
        self.stop()
        raise RuntimeError(f"the server did not become healthy within 90 s; see {self.log}")

    def __exit__(self, *exc: Any) -> None:
        self.stop()

    @property
    def pid(self) -> int:
        assert self.process is not None
        return self.process.pid

    def stop(self) -> None:
        process = self.process
        if process is not None and process.poll() is None:
            process.send_signal(signal.SIGTERM)
            try:
                process.wait(timeout=30)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait(timeout=10)
        out = self._out
        if out is not None:
            out.close()
            self._out = None

    def log_errors(self) -> list[str]:
        """Lines of the server log at level ERROR or CRITICAL, and tracebacks."""
        if not self.log.exists():
            return []
        lines = self.log.read_text(encoding="utf-8", errors="replace").splitlines()
        return [line for line in lines if " ERROR " in line or " CRITICAL " in line or line.startswith("Traceback")]


def _children(pid: int) -> list[int]:
    found = []
    for task in Path(f"/proc/{pid}/task").glob("*/children"):
        with contextlib.suppress(OSError):
            found += [int(c) for c in task.read_text().split()]
    return found


def _proc_sample(pid: int) -> tuple[float, float]:
    """(CPU seconds, resident MB) of one process, from ``/proc``."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    ticks = os.sysconf("SC_CLK_TCK")
    cpu = (int(fields[11]) + int(fields[12])) / ticks
    rss_pages = int(Path(f"/proc/{pid}/statm").read_text().split()[1])
    return cpu, rss_pages * os.sysconf("SC_PAGE_SIZE") / 2**20


def machine_busy_s() -> float:
    """CPU seconds the whole machine has spent busy (all cores, everything but idle and iowait)."""
    with contextlib.suppress(OSError, ValueError, IndexError):
        fields = [int(v) for v in Path("/proc/stat").read_text().splitlines()[0].split()[1:]]
        return (sum(fields[:8]) - fields[3] - fields[4]) / os.sysconf("SC_CLK_TCK")
    return 0.0


def sample_tree(pid: int) -> dict[str, float]:
    """CPU seconds and resident MB of the server process and of its children (the robot workers), and CPU
    seconds of this process (the simulated participants) and of the whole machine."""
    try:
        import psutil
    except ImportError:
        psutil = None
    out = {"server_cpu_s": 0.0, "server_rss_mb": 0.0, "workers_cpu_s": 0.0, "workers_rss_mb": 0.0,
           "clients_cpu_s": time.process_time(), "machine_cpu_s": machine_busy_s()}
    if psutil is not None:
        with contextlib.suppress(psutil.Error):
            root = psutil.Process(pid)
            for proc, prefix in [(root, "server"), *((c, "workers") for c in root.children(recursive=True))]:
                times, memory = proc.cpu_times(), proc.memory_info()
                out[f"{prefix}_cpu_s"] += times.user + times.system
                out[f"{prefix}_rss_mb"] += memory.rss / 2**20
        return out
    for proc, prefix in [(pid, "server"), *((c, "workers") for c in _children(pid))]:
        with contextlib.suppress(OSError, IndexError, ValueError):
            cpu, rss = _proc_sample(proc)
            out[f"{prefix}_cpu_s"] += cpu
            out[f"{prefix}_rss_mb"] += rss
    return out


class ResourceSampler:
    """Samples :func:`sample_tree` every ``interval`` seconds in a thread, from ``start_after`` seconds on
    (after the warm-up): CPU use over that time (100 % = one core) of the server, its robot workers, the
    simulated participants and everything else on the machine (``other``: other people's work skews a
    measurement), and the peak resident memory."""

    def __init__(self, pid: int, interval: float = 0.5, start_after: float = 0.0) -> None:
        self.pid, self.interval, self.start_after = pid, interval, start_after
        self.samples: list[tuple[float, dict[str, float]]] = []
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="resource-sampler", daemon=True)

    def __enter__(self) -> ResourceSampler:
        self._thread.start()
        return self

    def __exit__(self, *exc: Any) -> None:
        self._stop.set()
        self._thread.join(timeout=5)
        self.samples.append((time.monotonic(), sample_tree(self.pid)))

    def _run(self) -> None:
        if self._stop.wait(self.start_after):
            return
        self.samples.append((time.monotonic(), sample_tree(self.pid)))
        while not self._stop.wait(self.interval):
            self.samples.append((time.monotonic(), sample_tree(self.pid)))

    def summary(self) -> dict[str, float | None]:
        if len(self.samples) < 2:
            return {"server_cpu_percent": None, "workers_cpu_percent": None, "clients_cpu_percent": None,
                    "other_cpu_percent": None, "server_rss_mb_peak": None, "workers_rss_mb_peak": None}
        (t0, first), (t1, last) = self.samples[0], self.samples[-1]
        wall = max(t1 - t0, 1e-9)

        def percent(prefix: str) -> float:
            return round(100 * (last[f"{prefix}_cpu_s"] - first[f"{prefix}_cpu_s"]) / wall, 1)

        others = percent("machine") - percent("server") - percent("workers") - percent("clients")
        return {
            "server_cpu_percent": percent("server"), "workers_cpu_percent": percent("workers"),
            "clients_cpu_percent": percent("clients"), "other_cpu_percent": round(max(others, 0.0), 1),
            "server_rss_mb_peak": round(max(s["server_rss_mb"] for _, s in self.samples), 1),
            "workers_rss_mb_peak": round(max(s["workers_rss_mb"] for _, s in self.samples), 1),
        }
