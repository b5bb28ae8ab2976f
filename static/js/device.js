/**
 * The device check on landing: the browser reports its screen, window and pointers
 * (`POST /api/session/device`, stored with the participant); the server says whether the study can be taken
 * on it (a screen under the study's minimum, default 1024 × 600, or a device without a mouse or trackpad is
 * refused). The page then asks for a computer with a keyboard: the game's interrupts need one, and on a phone
 * the task buttons would be below the fold. It shows the session's hand-off code (`session.handoff.code`) and a
 * link carrying it: the computer continues this session only with one of them (docs/protocol.md §1).
 */

import { h, show } from "./dom.js";

/** What this browser can tell about its device (CSS pixels). */
export function deviceInfo(win = window) {
  const anyFine = win.matchMedia ? win.matchMedia("(any-pointer: fine)").matches : true;
  return {
    screen_width: Math.round(win.screen.width),
    screen_height: Math.round(win.screen.height),
    viewport_width: Math.round(win.innerWidth),
    viewport_height: Math.round(win.innerHeight),
    pixel_ratio: win.devicePixelRatio || 1,
    fine_pointer: anyFine,
    touch: (win.navigator.maxTouchPoints || 0) > 0,
  };
}

/** Whether the session's last device check refuses this device (the end pages are always shown). */
export function deviceRefused(session) {
  return Boolean(session.device && !session.device.ok && !["done", "screened_out"].includes(session.state));
}

export function devicePage(root, ctx) {
  const { device } = ctx.session;
  const reasons = [];
  if (device.problems.includes("small_screen")) {
    reasons.push(`This study needs a screen of at least ${device.min_width} × ${device.min_height} pixels; ` +
      "yours is smaller.");
  }
  if (device.problems.includes("touch_only")) {
    reasons.push("This study is played with a keyboard and a mouse or trackpad; this device seems to have only a " +
      "touch screen.");
  }
  const again = h("button", { type: "button", class: "primary", id: "device-again", onclick: async () => {
    again.disabled = true;
    try {
      ctx.route(await ctx.api.device(deviceInfo()));
    } catch {
      again.disabled = false;
    }
  } }, "Check again");
  const title = h("h1", { id: "device-title", tabindex: "-1" }, "Please use a computer with a keyboard");
  const code = ctx.session.handoff ? ctx.session.handoff.code : "";
  const link = `${window.location.origin}${window.location.pathname}${window.location.search}#handoff=${code}`;
  show(root, h("section", { class: "card narrow", id: "device", dataset: { problems: device.problems.join(" ") },
                            "aria-labelledby": "device-title" },
    title,
    reasons.map((text) => h("p", {}, text)),
    h("p", {}, "Please open the same study link on a laptop or desktop computer. Your place in the study is kept: " +
      "you continue where you are now."),
    code ? [
      h("p", {}, "The computer will ask for this code (it keeps your place yours; share it with nobody):"),
      h("p", { class: "handoff-code", id: "handoff-code" }, code),
      h("p", {}, "Or open this link on the computer: ", h("a", { href: link, id: "handoff-link" }, link)),
    ] : null,
    h("div", { class: "actions" }, again)), title);
}
