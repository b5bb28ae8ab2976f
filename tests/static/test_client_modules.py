"""The client's modules exercised one by one inside Chromium (imported as the pages import them): the key
map, repeat throttling, reconnect backoff, attention events, the safe Markdown renderer and the station
drawings' progress states."""

from __future__ import annotations

import pytest

pytestmark = pytest.mark.browser


def test_key_map(module_page):
    got = module_page.evaluate("""async () => {
      const { interruptForKey } = await import('/js/game/keys.js');
      const k = (init) => interruptForKey(new KeyboardEvent('keydown', init));
      return {
        arrowUp: k({ key: 'ArrowUp', code: 'ArrowUp' }), w: k({ key: 'w', code: 'KeyW' }),
        azertyZ: k({ key: 'z', code: 'KeyW' }), a: k({ key: 'a', code: 'KeyA' }), s: k({ key: 's', code: 'KeyS' }),
        capsS: k({ key: 'S', code: 'KeyS' }), shiftS: k({ key: 'S', code: 'KeyS', shiftKey: true }),
        d: k({ key: 'd', code: 'KeyD' }), space: k({ key: ' ', code: 'Space' }),
        escape: k({ key: 'Escape', code: 'Escape' }), dot: k({ key: '.', code: 'Period' }),
        ctrlS: k({ key: 's', code: 'KeyS', ctrlKey: true }), enter: k({ key: 'Enter', code: 'Enter' }),
      };
    }""")
    assert got == {"arrowUp": "up", "w": "up", "azertyZ": "up", "a": "left", "s": "down", "capsS": "down",
                   "shiftS": "stop", "d": "right", "space": "interact", "escape": "stop", "dot": "stay",
                   "ctrlS": None, "enter": None}


def test_held_keys_repeat_at_most_once_per_tick_and_typing_is_ignored(module_page):
    got = module_page.evaluate("""async () => {
      const { listenKeys } = await import('/js/game/keys.js');
      const seen = [];
      const stop = listenKeys(document, (a) => seen.push(a), { repeatMs: 150 });
      const fire = (target, init) => target.dispatchEvent(new KeyboardEvent('keydown', { bubbles: true, cancelable: true, ...init }));
      fire(document.body, { key: 'ArrowLeft', code: 'ArrowLeft' });
      for (let i = 0; i < 5; i += 1) fire(document.body, { key: 'ArrowLeft', code: 'ArrowLeft', repeat: true });
      await new Promise((r) => setTimeout(r, 200));
      fire(document.body, { key: 'ArrowLeft', code: 'ArrowLeft', repeat: true });
      const input = document.createElement('input');
      document.body.append(input);
      const typed = fire(input, { key: 'd', code: 'KeyD' });
      const prevented = !fire(document.body, { key: ' ', code: 'Space' });
      stop();
      fire(document.body, { key: 'd', code: 'KeyD' });
      return { seen, typed, prevented };
    }""")
    assert got == {"seen": ["left", "left", "interact"], "typed": True, "prevented": True}


def test_reconnect_backoff_grows_to_a_cap(module_page):
    got = module_page.evaluate("""async () => {
      const { backoffDelay } = await import('/js/game/connection.js');
      const at = (r) => [0, 1, 2, 3, 4, 5, 6, 9].map((n) => backoffDelay(n, () => r));
      return { low: at(0), mid: at(0.5), high: at(0.999) };
    }""")
    assert got["mid"] == [250, 500, 1000, 2000, 4000, 8000, 8000, 8000]
    assert all(lo < hi for lo, hi in zip(got["low"], got["high"]))
    assert got["low"][0] == 200 and got["high"][-1] <= 9600


def test_attention_events_report_changes_and_idle_periods(module_page):
    got = module_page.evaluate("""async () => {
      const { Activity } = await import('/js/game/activity.js');
      const sent = [];
      let online = false;
      const activity = new Activity((type, fields) => online ? (sent.push([type, fields ? fields.idle_ms : null]), 1) : null,
                                    { idleMs: 150, checkMs: 20 });
      window.dispatchEvent(new Event('blur'));
      online = true;
      activity.resync();
      window.dispatchEvent(new Event('blur'));
      window.dispatchEvent(new Event('focus'));
      window.dispatchEvent(new Event('focus'));
      await new Promise((r) => setTimeout(r, 400));
      window.dispatchEvent(new KeyboardEvent('keydown', { key: 'x' }));
      const before = sent.length;
      await new Promise((r) => setTimeout(r, 80));
      const quiet = sent.length === before;
      activity.destroy();
      return { sent, quiet };
    }""")
    kinds = [kind for kind, _ in got["sent"]]
    assert kinds == ["blur", "focus", "idle", "idle"], got
    idle = [ms for kind, ms in got["sent"] if kind == "idle"]
    assert 150 <= idle[0] < 300 and 300 <= idle[1] < 450
    assert got["quiet"], "input resets the idle clock"


def test_markdown_is_rendered_without_markup_injection(module_page):
    got = module_page.evaluate("""async () => {
      const { renderMarkdown } = await import('/js/markdown.js');
      const div = document.createElement('div');
      div.append(renderMarkdown('# Title\\n\\nHello **bold** and *it* <img src=x onerror=alert(1)>\\n\\n' +
        '- one\\n- two [site](https://example.org) [bad](javascript:alert(1))\\n\\n1. first'));
      return { html: div.innerHTML, imgs: div.querySelectorAll('img').length,
               links: [...div.querySelectorAll('a')].map((a) => a.getAttribute('href')) };
    }""")
    assert got["imgs"] == 0 and got["links"] == ["https://example.org"]
    assert got["html"].startswith("<h1>Title</h1><p>Hello <strong>bold</strong> and <em>it</em> &lt;img")
    assert "<ul><li>one</li><li>two" in got["html"] and "<ol><li>first</li></ol>" in got["html"]
    assert "[bad](javascript:alert(1))" in got["html"]


def test_each_station_state_and_progress_step_is_drawn_differently(module_page):
    got = module_page.evaluate("""async () => {
      const { drawCell } = await import('/js/game/stations.js');
      const picture = (cell) => {
        const c = document.createElement('canvas');
        c.width = c.height = 64;
        drawCell(c.getContext('2d'), cell, 0, 0, 64);
        return c.toDataURL();
      };
      const states = {
        grill: [['empty', 0, 10], ['cooking', 0, 10], ['cooking', 5, 10], ['ready', 10, 10]],
        board: [['empty', 0, 2], ['chopping', 0, 2], ['chopping', 1, 2], ['ready', 2, 2]],
        sink: [['empty', 0, 2], ['washing', 0, 2], ['washing', 1, 2], ['clean', 2, 2]],
      };
      const out = {};
      for (const [terrain, list] of Object.entries(states)) {
        out[terrain] = new Set(list.map(([state, progress, total]) => picture({ terrain, station: { state, progress, total } }))).size;
      }
      out.objects = new Set(['onion', 'meat', 'dirty_plate', 'clean_plate', 'steak_plate', 'dish', null]
        .map((object) => picture({ terrain: 'counter', object }))).size;
      return out;
    }""")
    assert got == {"grill": 4, "board": 4, "sink": 4, "objects": 7}


def test_the_instructions_never_invent_a_field_of_view(module_page):
    """Without the study's angle in the session view the page says so where the cone is explained and keeps
    the button disabled; with it, the text and the picture use that angle."""
    got = module_page.evaluate("""async () => {
      const { instructionsPage } = await import('/js/pages/instructions.js');
      const render = (session) => {
        const root = document.createElement('main');
        document.body.replaceChildren(root);
        instructionsPage(root, { session: { instructions: 'Read this.', ...session }, api: {}, route: () => {} });
        return {
          error: root.querySelector('#fov-error')?.textContent || null,
          text: root.querySelector('#fov-text')?.textContent || null,
          picture: root.querySelector('#instructions-picture') !== null,
          disabled: root.querySelector('#instructions-done').disabled,
          says120: root.textContent.includes('120°'),
        };
      };
      return { missing: render({}), nulled: render({ fov_angle: null }), text: render({ fov_angle: '90' }),
               zero: render({ fov_angle: 0 }), given: render({ fov_angle: 90 }) };
    }""")
    for case in ("missing", "nulled", "text", "zero"):
        page = got[case]
        assert page["error"] and "could not load the study's field of view" in page["error"], case
        assert (page["text"], page["picture"], page["disabled"], page["says120"]) == (None, False, True, False), case
    given = got["given"]
    assert given["error"] is None and "cone of 90°" in given["text"]
    assert (given["picture"], given["disabled"], given["says120"]) == (True, False, False)
