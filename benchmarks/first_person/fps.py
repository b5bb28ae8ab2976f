"""Frames per second of the first-person view, as a participant's browser draws them.

For each field of view asked (default 90°, 120° and 360°: one rectilinear render, the cylindrical lens with
two slices, with four), the script starts ``steakhouse serve`` on 127.0.0.1 with a one-trial study in that
view on the largest shipped kitchen (mid_2, 15 × 11), opens the participant link in Debian's Chromium with
software WebGL (SwiftShader: ``--use-gl=angle --use-angle=swiftshader``), sizes the kitchen's canvas to
exactly 1280 × 720 device pixels, and walks the cook around the kitchen with the arrow keys for ``--seconds``
(a key every tick: forward while the floor ahead is free, else turn left), with the FOV-aware robot moving
too. The view draws a frame in every animation frame while something glides between two ticks, so the
frames it counted over the walk, divided by the time, are the frames per second the participant got.

    .venv/bin/python benchmarks/first_person/fps.py [--seconds 20] [--fovs 90,120,360] [--json]

It prints, per field of view, the lens, the canvas size, frames, seconds, frames per second, how busy the
machine was meanwhile and its load average (all processes: software rendering shares the cores with the
server, the robot and anything else running).
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import yaml

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO))
sys.path.insert(0, str(REPO / "benchmarks" / "load"))

from bench_server import BenchServer, machine_busy_s  # noqa: E402

from planner.geometry import Direction  # noqa: E402
from study_config import load_layout  # noqa: E402

KITCHEN = "mid_2"
WEBGL_ARGS = ["--no-sandbox", "--use-gl=angle", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
              "--ignore-gpu-blocklist", "--disable-background-networking", "--no-first-run"]
STEP = {Direction.NORTH: (0, -1), Direction.SOUTH: (0, 1), Direction.EAST: (1, 0), Direction.WEST: (-1, 0)}
CANVAS = (1280, 720)


def write_study(folder: Path, fov: float) -> Path:
    path = folder / f"fps_{int(fov)}.yaml"
    path.write_text(yaml.safe_dump({
        "id": f"fps_{int(fov)}", "title": f"First-person frame rate at {fov} degrees", "kitchens": [KITCHEN],
        "robots": ["fov_aware"], "factors": ["robot"], "view": "first_person",
        "world": {"fov_angle": fov, "orders": 5, "horizon": 5000}}), encoding="utf-8")
    return path


def walk_and_count(page: Any, seconds: float, tick_s: float) -> tuple[int, float]:
    """Walk the cook for ``seconds``; returns (frames drawn, seconds elapsed) over the walk."""
    layout = load_layout(KITCHEN)

    def frames() -> int:
        return int(page.eval_on_selector("#kitchen", "el => el.dataset.frames"))

    start_frames, start = frames(), time.monotonic()
    while time.monotonic() - start < seconds:
        x, y, facing = page.eval_on_selector("#kitchen", "el => el.dataset.you").split(",")
        dx, dy = STEP[Direction(facing)]
        ahead = (int(x) + dx, int(y) + dy)
        page.keyboard.press("w" if ahead in layout.floor else "a")
        time.sleep(tick_s)
    return frames() - start_frames, time.monotonic() - start


def test_run_path(server: BenchServer, study_id: str) -> str:
    """The admin's signed test-run link of the study (a test run is only ever started from one)."""
    import httpx

    links = httpx.get(f"{server.url}/api/admin/studies/{study_id}/links", timeout=30,
                      headers={"Authorization": f"Bearer {server.admin_token}"})
    links.raise_for_status()
    return str(links.json()["test_run"]["path"])


def measure(fov: float, seconds: float, chromium: str, folder: Path) -> dict[str, Any]:
    from playwright.sync_api import sync_playwright

    study = write_study(folder, fov)
    with BenchServer(study=study, database_url=f"sqlite:///{folder / f'fps_{int(fov)}.sqlite3'}", workers=1,
                     log=folder / "server.log") as server, sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=chromium, headless=True, args=WEBGL_ARGS)
        try:
            page = browser.new_page(viewport={"width": 1760, "height": 1100}, device_scale_factor=1)
            page.goto(server.url + test_run_path(server, f"fps_{int(fov)}"))
            for selector in ("#consent-agree", "#instructions-done", "#start-round"):
                page.click(selector)
            page.wait_for_selector("#stage")
            page.evaluate("([w, h]) => Object.assign(document.querySelector('#stage').style,"
                          " { flex: 'none', width: `${w}px`, height: `${h}px` })", list(CANVAS))
            page.wait_for_function("() => { const c = document.querySelector('#kitchen');"
                                   " return c && +c.dataset.frames > 0; }", timeout=60_000)
            page.wait_for_timeout(1000)
            info = page.eval_on_selector("#kitchen", """el => {
              const gl = el.getContext('webgl2');
              const debug = gl.getExtension('WEBGL_debug_renderer_info');
              return { width: el.width, height: el.height, lens: el.dataset.lens,
                       renderer: debug ? gl.getParameter(debug.UNMASKED_RENDERER_WEBGL)
                                       : gl.getParameter(gl.RENDERER) };
            }""")
            busy_before, wall_before = machine_busy_s(), time.monotonic()
            frames, elapsed = walk_and_count(page, seconds, 0.2)
            busy = (machine_busy_s() - busy_before) / (time.monotonic() - wall_before)
        finally:
            browser.close()
    return {"fov": fov, **info, "frames": frames, "seconds": round(elapsed, 2), "fps": round(frames / elapsed, 1),
            "machine_busy_cores": round(busy, 2), "load_average": round(os.getloadavg()[0], 1)}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seconds", type=float, default=20.0, help="walking time per field of view (default 20)")
    parser.add_argument("--fovs", default="90,120,360", help="fields of view in degrees, comma-separated")
    parser.add_argument("--json", action="store_true", help="print the results as JSON")
    args = parser.parse_args(argv)
    chromium = shutil.which("chromium")
    if chromium is None:
        parser.error("Debian's chromium is not installed (make browser)")
    try:
        fovs = [float(f) for f in args.fovs.split(",")]
    except ValueError:
        parser.error(f"--fovs must be numbers separated by commas, got {args.fovs!r}")
    with tempfile.TemporaryDirectory(prefix="steakhouse-fps-") as tmp:
        results = [measure(fov, args.seconds, chromium, Path(tmp)) for fov in fovs]
    if args.json:
        print(json.dumps(results, indent=2))
        return 0
    print(f"first-person view on {KITCHEN}, canvas {CANVAS[0]}x{CANVAS[1]}, software WebGL; "
          f"{args.seconds:g} s walk each")
    print(f"renderer: {results[0]['renderer']}")
    print(f"{'fov':>5} {'lens':<12} {'canvas':<10} {'frames':>7} {'seconds':>8} {'fps':>6} {'busy cores':>11} "
          f"{'load avg':>9}")
    for r in results:
        print(f"{r['fov']:>5g} {r['lens']:<12} {r['width']}x{r['height']:<5} {r['frames']:>7} {r['seconds']:>8} "
              f"{r['fps']:>6} {r['machine_busy_cores']:>11} {r['load_average']:>9}")
    print(f"({os.cpu_count()} cores; load average: runnable processes on the whole machine, 1-minute mean)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
