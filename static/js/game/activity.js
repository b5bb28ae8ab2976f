/**
 * Attention events for exclusion rules (the admin excludes on them): `blur` when the tab is hidden or
 * the window loses focus, `focus` when it is back, and `idle` when there was no keyboard, mouse or touch
 * input for `idleMs` during a trial (reported again after every further `idleMs`, with the time since
 * the last input). Only changes are sent; `send(type, fields)` returns null when the game is offline,
 * in which case the change is sent once the connection is back (`resync`).
 */

export class Activity {
  constructor(send, { idleMs = 30000, checkMs = 1000 } = {}) {
    this.send = send;
    this.idleMs = idleMs;
    this.sent = "focus";
    this.lastInput = performance.now();
    this.idleReported = 0;
    this.onInput = () => {
      this.lastInput = performance.now();
      this.idleReported = 0;
    };
    this.blurred = false;
    this.onChange = (event) => this.report(event);
    for (const type of ["keydown", "pointerdown", "pointermove", "wheel", "touchstart"]) {
      window.addEventListener(type, this.onInput, { passive: true, capture: true });
    }
    window.addEventListener("focus", this.onChange);
    window.addEventListener("blur", this.onChange);
    document.addEventListener("visibilitychange", this.onChange);
    this.timer = window.setInterval(() => this.checkIdle(), checkMs);
  }

  /** Whether the participant is looking at the game now. */
  attending() {
    return document.visibilityState !== "hidden" && !this.blurred;
  }

  report(event) {
    const type = event ? event.type : null;
    if (type === "blur") this.blurred = true;
    if (type === "focus") this.blurred = false;
    this.resync();
  }

  /** Send the current focus state if it differs from the last one sent. */
  resync() {
    const now = this.attending() ? "focus" : "blur";
    if (now !== this.sent && this.send(now) !== null) this.sent = now;
  }

  checkIdle() {
    const quiet = performance.now() - this.lastInput;
    const due = (this.idleReported + 1) * this.idleMs;
    if (quiet >= due && this.send("idle", { idle_ms: Math.round(quiet) }) !== null) this.idleReported += 1;
  }

  destroy() {
    for (const type of ["keydown", "pointerdown", "pointermove", "wheel", "touchstart"]) {
      window.removeEventListener(type, this.onInput, { capture: true });
    }
    window.removeEventListener("focus", this.onChange);
    window.removeEventListener("blur", this.onChange);
    document.removeEventListener("visibilitychange", this.onChange);
    window.clearInterval(this.timer);
  }
}
