/** Shared page helpers: showing the error of a failed action, and plain message pages. */

import { h, show } from "../dom.js";

/**
 * Show why an action failed next to it. A 409 means the session moved on (another tab, a finished
 * round): the page is re-routed from the server's state instead. Returns whether it re-routed.
 */
export function actionError(exc, element, ctx) {
  if (exc.status === 409) {
    ctx.route();
    return true;
  }
  element.textContent = exc.status === 0
    ? "The server could not be reached. Check your internet connection and try again."
    : `Something went wrong (${exc.message}). Please try again.`;
  return false;
}

export function messagePage(root, title, text, action) {
  show(root, h("section", { class: "card narrow", id: "message", "aria-labelledby": "message-title" },
    h("h1", { id: "message-title" }, title),
    (Array.isArray(text) ? text : [text]).map((t) => h("p", {}, t)),
    action ? h("div", { class: "actions" }, action) : null));
}
