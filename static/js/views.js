/**
 * The kitchen view a round is drawn with, chosen by the server's `hello.view`: the top-down canvas
 * (game/renderer.js) or the first-person 3D view (firstperson/, loaded only when a round needs it, so a
 * top-down participant never downloads three.js). It sits above both: game/ imports nothing of firstperson/
 * (firstperson/ draws with game/'s palette and stations), so the choice between them is made here. Both answer the same calls: `configure(hello)`,
 * `update(state)`, `interruptFor(action)` (the interrupt a key or button sends: the same for top-down,
 * relative to the view in first person), `interruptSent(seq)`, `interruptLabels` and `destroy()`.
 */

import { KitchenView } from "./game/renderer.js";
import { RELATIVE_LABELS, Steering } from "./firstperson/steering.js";

class TopDown {
  constructor(stage, canvas) {
    this.view = new KitchenView(canvas, stage, { maxCell: 200 });
    this.interruptLabels = {};
  }

  configure(hello) {
    this.view.setGrid(hello.width, hello.height, hello.bounds);
  }

  update(state) {
    this.view.update(state);
  }

  interruptFor(action) {
    return action;
  }

  interruptSent() {}

  destroy() {
    this.view.destroy();
  }
}

/**
 * The first-person view with keys relative to the view (firstperson/steering.js). The 3D module is loaded on first use;
 * calls made before it is there are replayed (the fixed facts and the latest state).
 */
class FirstPerson {
  constructor(stage, canvas, options) {
    this.inner = null;
    this.hello = null;
    this.state = null;
    this.gone = false;
    this.steering = new Steering();
    this.interruptLabels = RELATIVE_LABELS;
    this.ready = import("./firstperson/view.js").then(({ FirstPersonView }) => {
      if (this.gone) return;
      canvas.remove();
      this.inner = new FirstPersonView(stage, options);
      if (this.hello) this.inner.configure(this.hello);
      if (this.state) this.inner.update(this.state);
    });
  }

  configure(hello) {
    this.hello = hello;
    if (this.inner) this.inner.configure(hello);
  }

  update(state) {
    this.state = state;
    this.steering.observe(state);
    if (this.inner) this.inner.update(state);
  }

  interruptFor(action) {
    return this.steering.interruptFor(action);
  }

  interruptSent(seq) {
    this.steering.sent(seq);
  }

  destroy() {
    this.gone = true;
    if (this.inner) this.inner.destroy();
  }
}

/**
 * The view for `view` ("top_down" or "first_person") in `stage`, drawing on `canvas` (top-down) or on a
 * WebGL canvas that replaces it with the same id (first person; `options` go to FirstPersonView).
 */
export function kitchenViewFor(view, stage, canvas, options = {}) {
  return view === "first_person" ? new FirstPerson(stage, canvas, options) : new TopDown(stage, canvas);
}
