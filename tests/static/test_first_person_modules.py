"""The first-person view's pure parts inside Chromium (imported as the page imports them): the lens's field of
view at the screen's edges, the keys relative to the view, the controllers' thumbstick; and, without a browser,
the vendored three.js against its pinned version and checksums, and a 3D model for every terrain and object."""

from __future__ import annotations

import hashlib
import math
import re
from pathlib import Path
from typing import get_args

import pytest

from planner.objects import OBJECTS
from server.protocol.server import TerrainName

REPO = Path(__file__).resolve().parents[2]
STATIC = REPO / "static"
FIVE_MB = 5 * 1024 * 1024


@pytest.fixture
def module_page(study_server, new_page):
    page, _ = new_page()
    page.goto(f"{study_server.url}/data/example_view.json")
    return page


@pytest.mark.browser
@pytest.mark.parametrize("fov", [60, 90, 100, 120, 180, 270, 360])
def test_the_screens_edges_are_the_field_of_views_edges(pure_module_page, fov):
    # Only the lens's pure functions are called: every angle reads the same page (one load instead of seven).
    got = pure_module_page.evaluate("""async (fov) => {
      const { lensFor, screenOf } = await import('/js/firstperson/lens.js');
      const lens = lensFor(fov, 16 / 9);
      const at = (deg) => screenOf(lens, deg * Math.PI / 180, -0.3);
      return { kind: lens.kind, slices: lens.slices || 0, centre: at(0), pitch: lens.pitch || 0,
               inside: [at(fov * 0.495), at(-fov * 0.495)],
               outside: fov < 360 ? [at(fov * 0.505), at(-fov * 0.505)] : [],
               // The counter in front (its top centre 1.3 m ahead and 0.58 m below the eyes) is in view.
               counter: screenOf(lens, 0, -Math.atan2(0.58, 1.3)) };
    }""", fov)
    assert got["kind"] == ("rectilinear" if fov <= 100 else "cylindrical")
    if got["kind"] == "cylindrical":
        assert got["slices"] == math.ceil(fov / 90)
    assert got["centre"][0] == pytest.approx(0.5)
    right, left = got["inside"]
    assert right is not None and left is not None and right[0] > 0.99 and left[0] < 0.01
    assert all(edge is None for edge in got["outside"])
    assert got["counter"] is not None and got["pitch"] == 0


@pytest.mark.browser
def test_keys_are_relative_to_the_view(module_page):
    got = module_page.evaluate("""async () => {
      const { Steering, directionFor } = await import('/js/firstperson/steering.js');
      const table = ['north', 'east', 'south', 'west'].map(
        (f) => ['up', 'right', 'down', 'left'].map((k) => directionFor(f, k)));
      const s = new Steering();
      const state = (facing, queued, ack) => ({ you: { facing }, queued, ack });
      s.observe(state('south', 0, 0));
      const first = [s.interruptFor('left'), s.interruptFor('up'), s.interruptFor('left')];
      s.sent(7);
      s.observe(state('east', 1, 6));            // the server has not played them all yet: keep our facing
      const queued = s.interruptFor('right');
      s.sent(8);
      s.observe(state('west', 0, 8));            // all played: the server's facing again
      return { table, first, queued, after: s.interruptFor('up'), other: s.interruptFor('interact') };
    }""")
    assert got["table"] == [["north", "east", "south", "west"], ["east", "south", "west", "north"],
                            ["south", "west", "north", "east"], ["west", "north", "east", "south"]]
    assert got["first"] == ["right", "right", "up"]
    assert got["queued"] == "right"
    assert got["after"] == "left" and got["other"] == "interact"


@pytest.mark.browser
def test_the_thumbstick_is_the_arrow_keys(module_page):
    got = module_page.evaluate("""async () => {
      const { stickKey } = await import('/js/firstperson/xr.js');
      return [stickKey(0, -1), stickKey(0, 0.9), stickKey(-0.8, 0.3), stickKey(0.7, -0.2), stickKey(0.3, -0.4)];
    }""")
    assert got == ["up", "down", "left", "right", None]


def test_three_is_vendored_at_its_pinned_version_unchanged():
    fetch = (STATIC / "vendor" / "fetch.sh").read_text(encoding="utf-8")
    pinned = re.search(r'"three (\S+) (sha512-\S+) static/vendor/three ([^"]+)"', fetch)
    assert pinned is not None
    version, _, files = pinned.groups()
    folder = STATIC / "vendor" / "three"
    assert (folder / "VERSION").read_text().strip() == f"three@{version}"
    listed = (folder / "SHA256SUMS").read_text().splitlines()
    sums = {name: digest for digest, name in (line.split() for line in listed)}
    names = {Path(f).name for f in files.split()}
    assert set(sums) == names | {"VERSION"}
    for name, digest in sums.items():
        data = (folder / name).read_bytes()
        assert hashlib.sha256(data).hexdigest() == digest, f"{name} differs from what fetch.sh fetched"
        assert len(data) < FIVE_MB
    assert f"REVISION = '{version.split('.')[1]}'" in (folder / "three.core.js").read_text(encoding="utf-8")
    assert "MIT License" in (folder / "LICENSE").read_text(encoding="utf-8")
    imported = {m for js in (STATIC / "js").rglob("*.js")
                for m in re.findall(r'vendor/three/([\w.]+)', js.read_text(encoding="utf-8"))}
    assert imported == {"three.module.js"}


def test_every_terrain_and_object_has_a_3d_model():
    stations = (STATIC / "js" / "firstperson" / "stations.js").read_text(encoding="utf-8")
    start = stations.index("export const TERRAIN = {")
    table = stations[start:stations.index("};", start)]
    assert set(re.findall(r"^  (\w+)[:,]", table, flags=re.MULTILINE)) == set(get_args(TerrainName))
    items = (STATIC / "js" / "firstperson" / "items.js").read_text(encoding="utf-8")
    table = items[items.index("export const ITEMS = {"):items.index("};", items.index("export const ITEMS"))]
    assert set(re.findall(r"^  (\w+)[:,]", table, flags=re.MULTILINE)) == set(OBJECTS)
