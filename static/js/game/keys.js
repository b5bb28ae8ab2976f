/**
 * Keyboard interrupts. Arrow keys and W/A/S/D move (by physical key position, so ZQSD on an AZERTY
 * keyboard works too), Space interacts, "." stays, Escape or Shift+S stops the current task.
 *
 * Plain S is "down" (W/A/S/D); stopping with S needs Shift, so a participant moving with WASD never
 * cancels their task by accident. Keys with Ctrl, Alt or Meta are left to the browser, and so is typing
 * in form fields.
 */

const BY_CODE = {
  ArrowUp: "up", ArrowDown: "down", ArrowLeft: "left", ArrowRight: "right",
  KeyW: "up", KeyA: "left", KeyS: "down", KeyD: "right",
  Space: "interact", Escape: "stop", Period: "stay", NumpadDecimal: "stay",
};

/** The interrupt for a keyboard event, or null when the key is not a game key. */
export function interruptForKey(event) {
  if (event.ctrlKey || event.altKey || event.metaKey) return null;
  if (event.code === "KeyS" && event.shiftKey) return "stop";
  if (event.key === ".") return "stay";
  if (event.key === " ") return "interact";
  return BY_CODE[event.code] || null;
}

function typing(target) {
  if (!(target instanceof Element)) return false;
  return Boolean(target.closest("input, textarea, select, [contenteditable=''], [contenteditable='true']"));
}

/**
 * Listen for game keys on `target` (the document) and call `onInterrupt(action, event)`. A held key
 * repeats at most once per `repeatMs` (one world tick), so the server's queue of three interrupts is not
 * flooded. Returns a function that removes the listeners.
 */
export function listenKeys(target, onInterrupt, { repeatMs = 200 } = {}) {
  let lastSent = -Infinity;
  let swallowSpaceUp = false;
  const down = (event) => {
    if (typing(event.target)) return;
    const action = interruptForKey(event);
    if (!action) return;
    event.preventDefault();
    if (action === "interact") swallowSpaceUp = true;
    const now = performance.now();
    if (event.repeat && now - lastSent < repeatMs) return;
    lastSent = now;
    onInterrupt(action, event);
  };
  const up = (event) => {
    if (event.code === "Space" && swallowSpaceUp) {
      event.preventDefault();
      swallowSpaceUp = false;
    }
  };
  target.addEventListener("keydown", down);
  target.addEventListener("keyup", up);
  return () => {
    target.removeEventListener("keydown", down);
    target.removeEventListener("keyup", up);
  };
}
