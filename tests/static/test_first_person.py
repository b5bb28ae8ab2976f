"""The first-person view in Chromium with software WebGL (SwiftShader): a round renders on a WebGL canvas with
lit pixels, keys relative to the view move and turn the avatar on the server, every `state` frame holds
only the cells in view and the scene draws exactly those, the admin sees the participant's camera on
request, and "Enter VR" is absent without WebXR and opens a session with an emulated headset (IWER)."""

from __future__ import annotations

import io
import json
import shutil
from pathlib import Path
from typing import Any

import pytest
from steakhouse_browser import FIRST_FRAME_TIMEOUT_MS, TIMEOUT_MS, kitchen, screenshot, start_first_round, wait_drawn
from steakhouse_study_server import ADMIN_TOKEN

from planner.fov import view
from planner.geometry import Direction

pytestmark = pytest.mark.browser

STUDY = "first_person"
# The smallest screen a study accepts by default (study_config/study/device.py): software WebGL draws every pixel
# on the CPU, and this is a third fewer pixels than 1280 x 720.
SMALL_LAPTOP = (1024, 600)
LAYOUT = kitchen("mid_2")
ROBOT = (10, 3)
IWER = Path(__file__).resolve().parent / "vendor" / "iwer" / "iwer.min.js"
SCREENS = Path("/work/screens/i17")


def keep(page: Any, name: str, *, full_page: bool = False) -> None:
    """Save a screenshot under test-output/screenshots (and /work/screens/i17 when that folder exists)."""
    path = screenshot(page, name, full_page=full_page)
    if SCREENS.is_dir():
        shutil.copy(path, SCREENS / path.name)


def record_states(page: Any) -> list[dict[str, Any]]:
    """Every `state` message the page's websocket receives, as parsed JSON (appended as they come)."""
    states: list[dict[str, Any]] = []

    def on_socket(ws: Any) -> None:
        def on_frame(payload: Any) -> None:
            message = json.loads(payload)
            if message.get("type") == "state":
                states.append(message)

        ws.on("framereceived", on_frame)

    page.on("websocket", on_socket)
    return states


def lit_fraction(page: Any, selector: str = "#kitchen") -> tuple[float, float]:
    """Share of the canvas's pixels that are not black, overall and in its top tenth."""
    from PIL import Image

    image = Image.open(io.BytesIO(page.locator(selector).screenshot())).convert("L")
    width, height = image.size
    data = image.tobytes()
    top = data[: width * (height // 10)]
    return sum(p > 24 for p in data) / len(data), sum(p > 24 for p in top) / len(top)


def human(server: Any, trial_id: int) -> tuple[tuple[int, int], str]:
    world = server.live(trial_id)["world"]["human"]
    return tuple(world["pos"]), world["facing"]


def test_a_first_person_round_renders_moves_and_masks(study_server, new_gl_page):
    page, _ = new_gl_page(viewport=SMALL_LAPTOP)
    states = record_states(page)
    start_first_round(page, study_server.link(STUDY))
    drawn = wait_drawn(page, "d.view === 'first_person' && +d.frames > 0", timeout=FIRST_FRAME_TIMEOUT_MS)
    assert drawn.pos == (3, 2) and drawn.facing is Direction.SOUTH
    gl = page.eval_on_selector("#kitchen", "el => [el.getContext('webgl2') !== null, el.getContext('2d') === null,"
                                           " el.dataset.lens, el.width, el.height]")
    assert gl[:3] == [True, True, "cylindrical"] and gl[3] > 300 and gl[4] > 200
    page.wait_for_timeout(300)
    lit, lit_top = lit_fraction(page)
    assert lit > 0.35, f"only {lit:.0%} of the view is lit"
    assert lit_top < 0.05, "above the far counters is darkness, not a sky or walls"
    keep(page, "first_person_start")
    assert page.query_selector("#enter-vr") is None, "no WebXR here, so no Enter VR button"

    # Keys are relative to the view: left turns (and steps) left, W forward, S turns around, D turns right.
    trial_id = drawn.trial
    for key, pos, facing in (("ArrowLeft", (4, 2), "east"), ("w", (5, 2), "east"), ("s", (4, 2), "west"),
                             ("d", (4, 1), "north")):
        page.keyboard.press(key)
        wait_drawn(page, f"d.you === '{pos[0]},{pos[1]},{facing}'")
        assert human(study_server, trial_id) == (pos, facing)
    page.wait_for_timeout(400)
    keep(page, "first_person_facing_the_wall")
    lit_wall, _ = lit_fraction(page)
    assert lit_wall < lit, "facing the back wall, less of the kitchen is in view"

    assert len(states) >= 5
    for state in states:
        you = state["you"]
        seen = view(LAYOUT, (you["x"], you["y"]), Direction(you["facing"]), 120).cells
        assert {(c["x"], c["y"]) for c in state["cells"]} == seen, f"tick {state['tick']} sent cells out of view"
        assert (state["robot"] is not None) == (ROBOT in seen)
    last = states[-1]
    drawn_cells = page.eval_on_selector("#kitchen", "el => el.dataset.drawn").split(";")
    expected = sorted(((c["x"], c["y"]) for c in last["cells"]), key=lambda c: (c[1], c[0]))
    assert drawn_cells == [f"{x},{y}" for x, y in expected], "the scene draws the latest frame's cells only"

    # The experimenter: top-down picture with the FOV, plus the participant's camera on request.
    admin, _ = new_gl_page(viewport=SMALL_LAPTOP)
    admin.goto(f"{study_server.url}/admin/#/live/{trial_id}")
    admin.fill("#admin-token", ADMIN_TOKEN)
    admin.click("#login-submit")
    admin.wait_for_selector("#camera-toggle", state="visible", timeout=TIMEOUT_MS)
    assert admin.is_hidden("#participant-camera")
    admin.click("#camera-toggle")
    admin.wait_for_function("() => { const c = document.querySelector('#camera-canvas');"
                            " return c && +c.dataset.frames > 0 && c.dataset.you === '4,1,north'; }",
                            timeout=FIRST_FRAME_TIMEOUT_MS)
    camera_cells = admin.eval_on_selector("#camera-canvas", "el => el.dataset.drawn").split(";")
    fov = study_server.live(trial_id)["fov_cells"]
    assert camera_cells == [f"{x},{y}" for x, y in fov], "the camera shows what the participant's screen showed"
    keep(admin, "first_person_admin_live_camera", full_page=True)

    # The replay of the same trial draws the participant's camera of the tick shown (tick 0: the start).
    admin.goto(f"{study_server.url}/admin/#/replay/{trial_id}")
    admin.click("#camera-toggle")
    admin.wait_for_function("() => { const c = document.querySelector('#camera-canvas');"
                            " return c && +c.dataset.frames > 0 && c.dataset.tick === '0'; }",
                            timeout=FIRST_FRAME_TIMEOUT_MS)
    first = study_server.get(f"/api/admin/trials/{trial_id}/frames", start=0, limit=1)["frames"][0]
    camera_cells = admin.eval_on_selector("#camera-canvas", "el => el.dataset.drawn").split(";")
    assert (first["human"]["x"], first["human"]["y"]) == (3, 2)
    assert camera_cells == [f"{x},{y}" for x, y in first["fov"]]
    keep(admin, "first_person_admin_replay_camera", full_page=True)


def test_enter_vr_opens_a_session_with_an_emulated_headset(study_server, new_gl_page):
    page, _ = new_gl_page(viewport=SMALL_LAPTOP)
    page.add_init_script(IWER.read_text(encoding="utf-8") + """
      window.__xrDevice = new IWER.XRDevice(IWER.metaQuest3);
      window.__xrDevice.installRuntime({ forceInstall: true });""")
    start_first_round(page, study_server.link(STUDY))
    drawn = wait_drawn(page, "d.view === 'first_person' && +d.frames > 0", timeout=FIRST_FRAME_TIMEOUT_MS)
    page.wait_for_selector("#enter-vr", timeout=TIMEOUT_MS)
    page.click("#enter-vr")
    page.wait_for_selector("#enter-vr[data-presenting='true']", timeout=TIMEOUT_MS)
    before = int(page.eval_on_selector("#kitchen", "el => el.dataset.frames"))
    page.wait_for_function(f"() => +document.querySelector('#kitchen').dataset.frames > {before + 5}",
                           timeout=TIMEOUT_MS)
    # The right thumbstick pushed left and held: one snap turn left (east, from the start facing south),
    # stepping to (4, 2); then the trigger interacts with the counter ahead (an event the server logs).
    page.evaluate("() => window.__xrDevice.controllers.right.updateAxes('thumbstick', -1, 0)")
    wait_drawn(page, "d.you === '4,2,east'")
    page.wait_for_timeout(500)
    page.evaluate("() => window.__xrDevice.controllers.right.updateAxes('thumbstick', 0, 0)")
    assert human(study_server, drawn.trial) == ((4, 2), "east")
    page.evaluate("() => window.__xrDevice.controllers.right.updateButtonValue('trigger', 1)")
    page.wait_for_timeout(300)
    page.evaluate("() => window.__xrDevice.controllers.right.updateButtonValue('trigger', 0)")
    events = study_server.events(drawn.trial, until=lambda kinds: kinds.count("interrupt") >= 2)
    assert [e["payload"]["action"] for e in events if e["kind"] == "interrupt"] == ["right", "interact"]
    # Leaving VR from the headset (its system menu ends the session): the page draws the view again.
    page.evaluate("() => window.__xrDevice.activeSession.end()")
    page.wait_for_function("() => !document.querySelector('#enter-vr').dataset.presenting", timeout=TIMEOUT_MS)
    before = int(page.eval_on_selector("#kitchen", "el => el.dataset.frames"))
    page.keyboard.press("w")
    wait_drawn(page, f"d.you === '5,2,east' && +d.frames > {before}")


def test_a_first_person_study_teaches_its_own_keys_and_shows_the_dark_in_3d(study_server, new_gl_page):
    page, _ = new_gl_page(viewport=(1280, 720))
    page.goto(study_server.link(STUDY))
    page.click("#consent-agree")
    page.wait_for_selector("#instructions")
    rows = page.eval_on_selector_all("#keys-first-person tbody tr", "rs => rs.map(r => r.innerText.split('\\t'))")
    assert [r[0] for r in rows[:4]] == ["Forward", "Turn left", "Turn around", "Turn right"]
    assert "walk one cell ahead" in rows[0][2] and "step there when the floor is free" in rows[1][2]
    assert page.query_selector("#keys-top-down") is None, "no top-down key table for a first-person study"
    assert page.query_selector("#instructions-picture") is None, "nor the top-down picture"
    assert "The robot sees the whole kitchen" in page.inner_text("#fp-text")
    page.wait_for_function("() => { const c = document.querySelector('#fp-picture-canvas');"
                           " return c && +c.dataset.frames > 0; }", timeout=FIRST_FRAME_TIMEOUT_MS)
    page.wait_for_timeout(300)
    lit, lit_top = lit_fraction(page, "#fp-picture-canvas")
    assert 0.2 < lit < 0.9, f"{lit:.0%} of the picture is lit: the kitchen ahead, the rest dark"
    assert lit_top < 0.05
    drawn = page.eval_on_selector("#fp-picture-canvas", "el => [el.dataset.you, el.dataset.robot, el.dataset.drawn]")
    example = json.loads((Path(__file__).resolve().parents[2] / "static/data/example_view.json").read_text())
    assert drawn[0] == "5,2,east" and drawn[1] == "", "the example's cook facing east; the robot behind is dark"
    assert sorted(drawn[2].split(";")) == sorted(f"{x},{y}" for x, y in example["visible"])
    page.locator("#fp-picture").scroll_into_view_if_needed()
    keep(page, "first_person_instructions_picture")
    page.locator("#keys-first-person").scroll_into_view_if_needed()
    keep(page, "first_person_instructions_keys")


def test_the_chopped_onion_has_the_same_colour_seen_from_above_and_in_3d(study_server, new_gl_page):
    page, _ = new_gl_page(viewport=SMALL_LAPTOP)
    page.goto(f"{study_server.url}/data/example_view.json")
    colours = page.evaluate("""async () => {
      const { COLORS } = await import('/js/game/palette.js');
      const { itemModel } = await import('/js/firstperson/items.js');
      const cubes = [];
      itemModel('dish').traverse((o) => { if (o.isMesh && o.geometry.type === 'BoxGeometry'
        && o.geometry.parameters.width < 0.05) cubes.push('#' + o.material.color.getHexString()); });
      return { onion: COLORS.onion.toLowerCase(), cubes };
    }""")
    assert colours["cubes"] and set(colours["cubes"]) == {colours["onion"]}, colours
