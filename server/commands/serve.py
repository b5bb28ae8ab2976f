"""``steakhouse serve``: run the study server (FastAPI on uvicorn).

Options override the ``STEAKHOUSE_*`` environment (see :mod:`server.settings`); without ``--study`` the
shipped ``demo.yaml``, ``demo_first_person.yaml`` and ``paper_study.yaml`` are served; without
``--database-url`` (or ``DATABASE_URL``) the store is the SQLite file ``./data/steakhouse.sqlite3``, created
with its folder. Invalid settings or study files stop the command with every problem listed (exit 1).

Participant tokens never reach the log: the websocket takes ``?token=…`` (browsers cannot set headers
there) and uvicorn logs the path with its query (``"WebSocket /ws/play?token=…" [accepted]`` at info, and
HTTP requests in its access log), so the command installs :class:`RedactTokens` on uvicorn's loggers.
A text frame that is not valid UTF-8 is closed by uvicorn itself with 1007 (invalid frame payload data); it
logs that with a traceback, which :class:`QuietBadFrames` turns into one warning line.
"""

from __future__ import annotations

import argparse
import gc
import logging
import re
import sys
from typing import Any

from server.cli import UsageError

UVICORN_LOGGERS = ("uvicorn.error", "uvicorn.access")
_TOKEN = re.compile(r"([?&]token=)[^&\s\"']*")


class RedactTokens(logging.Filter):
    """Replaces the value of every ``token=`` query parameter in a log record by ``[redacted]``.

    The message and each string argument are redacted separately, so the argument tuple keeps its shape
    (uvicorn's access formatter unpacks it).
    """

    def filter(self, record: logging.LogRecord) -> bool:
        if isinstance(record.msg, str):
            record.msg = redact(record.msg)
        if isinstance(record.args, tuple):
            record.args = tuple(redact(a) if isinstance(a, str) else a for a in record.args)
        elif isinstance(record.args, dict):
            record.args = {k: redact(v) if isinstance(v, str) else v for k, v in record.args.items()}
        return True


class QuietBadFrames(logging.Filter):
    """uvicorn's record of a websocket text frame that is not valid UTF-8 (the socket is already closed with
    1007): one warning line without the traceback, since a client's bad bytes are not a server error."""

    def filter(self, record: logging.LogRecord) -> bool:
        if record.exc_info and isinstance(record.exc_info[1], UnicodeDecodeError):
            record.exc_info, record.exc_text = None, None
            record.levelno, record.levelname = logging.WARNING, "WARNING"
            record.msg, record.args = "websocket closed with 1007: a text frame was not valid UTF-8", ()
        return True


def redact(text: str) -> str:
    return _TOKEN.sub(r"\1[redacted]", text)


def install_redaction(names: tuple[str, ...] = UVICORN_LOGGERS) -> None:
    """Put one :class:`RedactTokens` and one :class:`QuietBadFrames` on each named logger (idempotent)."""
    for name in names:
        logger = logging.getLogger(name)
        for kind in (RedactTokens, QuietBadFrames):
            if not any(isinstance(f, kind) for f in logger.filters):
                logger.addFilter(kind())


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("serve", help="run the study server",
                                   description="Run the study server (participant pages, websocket, admin API).")
    parser.add_argument("--host", help="interface to listen on (default 127.0.0.1; 0.0.0.0 in a container)")
    parser.add_argument("--port", type=int, help="TCP port (default 8000)")
    parser.add_argument("--study", action="append", metavar="FILE", dest="studies",
                        help="study YAML to serve (repeatable; default: the shipped demo studies and the paper study)")
    parser.add_argument("--database-url", metavar="URL",
                        help="SQLAlchemy URL of the store (default: sqlite:///./data/steakhouse.sqlite3)")
    parser.add_argument("--workers", type=int, metavar="N", dest="robot_workers",
                        help="robot planner worker processes (default: CPU count; 0 = in the server process)")
    parser.add_argument("--static", metavar="DIR", dest="static_dir", help="folder of the browser client")
    parser.add_argument("--log-level", choices=("debug", "info", "warning", "error"))
    parser.set_defaults(handler=serve, subparser=parser)


def serve(args: argparse.Namespace) -> int:
    import uvicorn
    from pydantic import ValidationError

    from planner.layout import LayoutError
    from server.admin.links import start_banner
    from server.admin.test_links import signing_key
    from server.app import create_app
    from server.settings import Settings
    from study_config.catalog import DuplicateStudyError
    from study_config.study import StudyConfigError

    overrides: dict[str, Any] = {name: getattr(args, name) for name in
                                 ("host", "port", "database_url", "robot_workers", "static_dir", "log_level")
                                 if getattr(args, name) is not None}
    if args.studies:
        overrides["study_files"] = tuple(args.studies)
    try:
        settings = Settings(**overrides)
    except ValidationError as exc:
        problems = "; ".join(f"{'.'.join(str(p) for p in e['loc'])}: {e['msg']}" for e in exc.errors())
        raise UsageError(f"invalid settings: {problems}") from None
    logging.basicConfig(level=settings.log_level.upper(), format="%(asctime)s %(levelname)s %(name)s: %(message)s")
    if settings.log_level != "debug":
        logging.getLogger("alembic").setLevel(logging.WARNING)
    try:
        app = create_app(settings)
    except StudyConfigError as exc:
        for problem in exc.problems:
            print(problem, file=sys.stderr)
        print("the server did not start: fix the study file(s) above", file=sys.stderr)
        return 1
    except (LayoutError, DuplicateStudyError) as exc:
        print(f"{exc}\nthe server did not start", file=sys.stderr)
        return 1
    install_redaction()
    shown_host = "127.0.0.1" if settings.host in ("0.0.0.0", "::") else settings.host
    for line in start_banner(app.state.catalog, f"http://{shown_host}:{settings.port}",
                             signing_key(app.state.admin_token)):
        print(line, file=sys.stderr if line.startswith("WARNING") else sys.stdout, flush=True)
    _freeze_startup_objects()
    uvicorn.run(app, host=settings.host, port=settings.port, log_level=settings.log_level,
                ws_max_size=settings.ws_max_frame_bytes, timeout_graceful_shutdown=5)
    return 0


def _freeze_startup_objects() -> None:
    """Move everything built so far (modules, the app, the studies) out of the garbage collector's sight.

    A full collection walks every tracked object; in a serving process most of them are these, alive until
    exit, and walking them paused the game loop for 110–130 ms at a time (measured with ``gc.callbacks``
    under ``benchmarks/load/run.py``: ticks that late, and now and then a robot decision that missed its
    deadline). Objects made later are collected as usual."""
    gc.collect()
    gc.freeze()
