/**
 * The first-person kitchen: a WebGL canvas showing the server's `state` messages through the cook's eyes
 * (the participant's view of a `first_person` study, docs/client.md). The same interface as the top-down
 * KitchenView (`setGrid`, `update`, `destroy`) plus `configure(hello)` for the field of view and the tick
 * period. The participant's page wraps it with the keys relative to the view (static/js/views.js); the admin's
 * replay shows it as the participant's camera.
 *
 * Frames are drawn in requestAnimationFrame while something glides between two ticks (motion.js) or after a
 * new message or resize, and not at all while nothing changes. The canvas's data attributes say what was
 * drawn, as the top-down canvas's do: `tick`, `you`, `held`, `robot`, `visible` (cells in the message),
 * `drawn` (the cells drawn), `frames` (frames rendered), `lens` and `fov`.
 */

import * as THREE from "../../vendor/three/three.module.js";
import { heldLabel } from "../labels.js";
import { handsModel } from "./agents.js";
import { EyeCamera } from "./camera.js";
import { KitchenScene } from "./scene.js";
import { XrButton } from "./xr.js";

const MAX_PIXEL_RATIO = 2;

export class FirstPersonView {
  /**
   * `container`: the element the canvas fills. Options: `id` of the canvas, `label` (state → text
   * alternative), `xr` (offer "Enter VR" where the browser supports it), `onInterrupt` (XR controllers' moves).
   */
  constructor(container, { id = "kitchen", label = null, xr = false, onInterrupt = null } = {}) {
    this.container = container;
    this.label = label;
    this.canvas = document.createElement("canvas");
    this.canvas.id = id;
    this.canvas.className = "kitchen-canvas kitchen-3d";
    this.canvas.setAttribute("role", "img");
    this.canvas.dataset.view = "first_person";
    container.prepend(this.canvas);
    this.renderer = new THREE.WebGLRenderer({ canvas: this.canvas, antialias: false, powerPreference: "high-performance" });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, MAX_PIXEL_RATIO));
    this.kitchen = new KitchenScene();
    this.eye = new EyeCamera(this.kitchen.head);
    this.fov = 120;
    this.tickMs = 200;
    this.width = 0;
    this.height = 0;
    this.frames = 0;
    this.raf = 0;
    this.held = undefined;
    this.size = "";
    this.resizer = new ResizeObserver(() => this.invalidate());
    this.resizer.observe(container);
    this.xr = xr ? new XrButton(this, container, onInterrupt) : null;
  }

  /** The fixed facts of the round from `hello`: field of view and tick period. */
  configure(hello) {
    this.fov = hello.fov_angle;
    this.tickMs = 1000 / hello.tick_rate_hz;
    /** Whether a held control walks on: not on the paper's clock, where a held control is one press. */
    this.repeats = hello.mode !== "wait_for_participant";
    this.canvas.dataset.trial = String(hello.trial.id);
    this.size = "";
    this.setGrid(hello.width, hello.height);
  }

  setGrid(width, height) {
    this.width = width;
    this.height = height;
    this.invalidate();
  }

  setFov(angle) {
    if (angle === this.fov) return;
    this.fov = angle;
    this.size = "";
    this.invalidate();
  }

  update(state) {
    this.kitchen.update(state, performance.now(), this.tickMs);
    if (state.you.held !== this.held) {
      this.held = state.you.held;
      this.eye.setHands(handsModel(this.held));
    }
    this.describe(state);
    this.invalidate();
  }

  invalidate() {
    if (this.raf || this.renderer.xr.isPresenting) return;
    this.raf = window.requestAnimationFrame((now) => {
      this.raf = 0;
      if (this.draw(now)) this.invalidate();
    });
  }

  /** Fit the drawing buffer to the container (device pixels) and set the lens for its shape. */
  fit() {
    const w = Math.max(this.container.clientWidth, 1);
    const h = Math.max(this.container.clientHeight, 1);
    const size = `${w}x${h}@${this.fov}`;
    if (size === this.size) return;
    this.size = size;
    this.renderer.setSize(w, h, false);
    Object.assign(this.canvas.style, { width: `${w}px`, height: `${h}px`, left: "0px", top: "0px" });
    const buffer = this.renderer.getDrawingBufferSize(new THREE.Vector2());
    const lens = this.eye.configure(this.fov, buffer.x, buffer.y);
    this.canvas.dataset.lens = lens.kind;
    this.canvas.dataset.fov = String(this.fov);
  }

  /** Draw one frame at time `now`; true while the agents still glide (draw again next frame). */
  draw(now = performance.now()) {
    this.fit();
    const moving = this.kitchen.pose(now);
    this.eye.render(this.renderer, this.kitchen.scene);
    this.frames += 1;
    this.canvas.dataset.frames = String(this.frames);
    return moving;
  }

  describe(state) {
    const d = this.canvas.dataset;
    d.grid = `${this.width}x${this.height}`;
    d.tick = String(state.tick);
    d.you = `${state.you.x},${state.you.y},${state.you.facing}`;
    d.held = state.you.held || "";
    d.robot = state.robot ? `${state.robot.x},${state.robot.y},${state.robot.facing}` : "";
    d.visible = String(state.cells.length);
    d.drawn = this.kitchen.drawnCells().join(";");
    const text = this.label ? this.label(state) : `Your view of the kitchen, through your eyes: you face ` +
      `${state.you.facing} and hold ${heldLabel(state.you.held)}. ` +
      `${state.robot ? "The robot is in view." : "The robot is out of view."} What is outside your view is dark.`;
    if (this.canvas.getAttribute("aria-label") !== text) this.canvas.setAttribute("aria-label", text);
  }

  destroy() {
    if (this.raf) window.cancelAnimationFrame(this.raf);
    this.raf = 0;
    this.resizer.disconnect();
    if (this.xr) this.xr.destroy();
    this.eye.dispose();
    this.renderer.dispose();
    this.canvas.remove();
  }
}
