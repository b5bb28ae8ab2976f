/**
 * "Enter VR": the same first-person scene in a WebXR `immersive-vr` session, for a headset's browser. The
 * button exists only when `navigator.xr.isSessionSupported("immersive-vr")` says yes, so desktops never show
 * it. (three.js's own VRButton is not used: it shows a "VR not supported" button where this must show none.)
 *
 * In the headset the participant sits, as the paper's VR participants did: the body turns with the cook's
 * facing, the head looks around freely, and what lies outside the server's field of view is dark whatever the
 * head does (the server masks by the cook's facing, docs/domain.md §2). Controllers (the xr-standard mapping):
 * the thumbstick is the arrow keys (forward, turn left / right, turn around; held forward it walks on, once per
 * tick, while a turn is one snap turn per push),
 * the trigger interacts, the grip stops the task, the A / X button stays. What the cook holds sits in the
 * right controller's grip. The subtask buttons and the HUD stay on the page, usable after leaving VR.
 */

import { h } from "../dom.js";
import * as THREE from "../../vendor/three/three.module.js";
import { itemModel } from "./items.js";

const STICK = 0.6;

/** Whether this browser can open an immersive VR session (false when WebXR is absent or says no). */
export async function vrSupported() {
  if (!("xr" in navigator) || !navigator.xr) return false;
  try {
    return await navigator.xr.isSessionSupported("immersive-vr");
  } catch {
    return false;
  }
}

/** The direction key (game/keys.js names) a thumbstick position means, or null near the centre. */
export function stickKey(x, y) {
  if (Math.max(Math.abs(x), Math.abs(y)) < STICK) return null;
  if (Math.abs(y) >= Math.abs(x)) return y < 0 ? "up" : "down";
  return x < 0 ? "left" : "right";
}

export class XrButton {
  constructor(view, container, onInterrupt) {
    this.view = view;
    this.onInterrupt = onInterrupt || (() => {});
    this.session = null;
    this.button = null;
    this.container = container;
    this.held = new Map();
    this.gone = false;
    vrSupported().then((yes) => {
      if (!yes || this.gone) return;
      this.button = h("button", { type: "button", class: "enter-vr primary", id: "enter-vr", onclick: () => this.toggle() },
        "Enter VR");
      container.append(this.button);
    });
  }

  async toggle() {
    if (this.session) {
      await this.session.end();
      return;
    }
    const session = await navigator.xr.requestSession("immersive-vr", { optionalFeatures: ["local-floor"] });
    this.start(session);
  }

  async start(session) {
    const { renderer, kitchen } = this.view;
    this.session = session;
    renderer.xr.enabled = true;
    renderer.xr.setReferenceSpaceType("local");
    await renderer.xr.setSession(session);
    this.controllers = [0, 1].map((i) => {
      const grip = renderer.xr.getControllerGrip(i);
      kitchen.head.add(grip);
      return grip;
    });
    this.hands = null;
    session.addEventListener("select", () => this.send("interact"));
    session.addEventListener("squeeze", () => this.send("stop"));
    session.addEventListener("end", () => this.stop());
    this.button.textContent = "Exit VR";
    this.button.dataset.presenting = "true";
    renderer.setAnimationLoop((now) => this.frame(now));
  }

  send(action) {
    this.onInterrupt(action);
  }

  /** One headset frame: poll the controllers, glide the agents, draw the scene from the headset's eyes. */
  frame(now) {
    const { renderer, kitchen } = this.view;
    for (const source of this.session ? this.session.inputSources : []) {
      const pad = source.gamepad;
      if (!pad) continue;
      const key = stickKey(pad.axes[2] ?? 0, pad.axes[3] ?? 0);
      this.repeat(`${source.handedness}:stick`, key, now);
      this.repeat(`${source.handedness}:a`, pad.buttons[4] && pad.buttons[4].pressed ? "stay" : null, now);
    }
    if (!this.hands || this.hands.userData.held !== this.view.held) {
      if (this.hands) this.controllers[1].remove(this.hands);
      this.hands = this.view.held ? itemModel(this.view.held) : new THREE.Group();
      this.hands.position.set(0, 0.02, -0.12);
      this.hands.userData.held = this.view.held;
      this.controllers[1].add(this.hands);
    }
    kitchen.pose(now);
    renderer.render(kitchen.scene, this.view.eye.camera);
    this.view.frames += 1;
    this.view.canvas.dataset.frames = String(this.view.frames);
  }

  /** Send `action` when a control is first pushed; held forward, it walks on (again every tick; not on the
   * paper's clock, where a held control is one push), while a turn is one snap turn per push, as headset users
   * expect. */
  repeat(control, action, now) {
    const last = this.held.get(control);
    if (!action) {
      this.held.delete(control);
      return;
    }
    const walksOn = action === "up" && this.view.repeats !== false;
    if (last && last.action === action && (!walksOn || now - last.at < this.view.tickMs)) return;
    this.held.set(control, { action, at: now });
    this.send(action);
  }

  stop() {
    const { renderer } = this.view;
    renderer.setAnimationLoop(null);
    for (const grip of this.controllers || []) grip.removeFromParent();
    this.session = null;
    if (this.button) {
      this.button.textContent = "Enter VR";
      delete this.button.dataset.presenting;
    }
    this.view.size = "";
    this.view.invalidate();
  }

  destroy() {
    this.gone = true;
    if (this.session) this.session.end().catch(() => {});
    if (this.button) this.button.remove();
  }
}
