/**
 * Tiny DOM helpers: `h(tag, attrs, ...children)` builds elements without innerHTML, so text from the
 * server is always inserted as text.
 */

export function h(tag, attrs = {}, ...children) {
  const el = document.createElement(tag);
  for (const [key, value] of Object.entries(attrs || {})) {
    if (value === undefined || value === null || value === false) continue;
    if (key === "class") el.className = value;
    else if (key === "dataset") Object.assign(el.dataset, value);
    else if (key.startsWith("on") && typeof value === "function") el.addEventListener(key.slice(2), value);
    else if (value === true) el.setAttribute(key, "");
    else el.setAttribute(key, String(value));
  }
  append(el, children);
  return el;
}

function append(el, children) {
  for (const child of children.flat(Infinity)) {
    if (child === undefined || child === null || child === false) continue;
    el.append(child instanceof Node ? child : document.createTextNode(String(child)));
  }
}

/** Replace the contents of `root` with `children` and move keyboard focus to `focus` (or the root). */
export function show(root, children, focus) {
  root.replaceChildren();
  append(root, [children]);
  const target = focus || root;
  if (target === root && !root.hasAttribute("tabindex")) root.setAttribute("tabindex", "-1");
  window.scrollTo(0, 0);
  target.focus({ preventScroll: true });
}

/** Set the small "step x of y" note in the top bar. */
export function setProgress(text) {
  const el = document.getElementById("progress");
  if (el) el.textContent = text || "";
}
