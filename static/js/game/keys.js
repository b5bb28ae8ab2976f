/**
 * Keyboard interrupts. Arrow keys and W/A/S/D move (by physical key position, so ZQSD on an AZERTY
 * keyboard works too), Space interacts, "." stays, Escape or Shift+S stops the current task. The number row
 * (1–9, 0, -, =; by position, so an AZERTY row works unshifted) chooses a task: the nth task key is shown on
 * its button (game/controls.js), so a timed round is playable from the keyboard without tabbing.
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

/** The task keys in the order the task buttons are numbered (physical positions of the number row). */
export const TASK_KEYS = [
  { code: "Digit1", label: "1" }, { code: "Digit2", label: "2" }, { code: "Digit3", label: "3" },
  { code: "Digit4", label: "4" }, { code: "Digit5", label: "5" }, { code: "Digit6", label: "6" },
  { code: "Digit7", label: "7" }, { code: "Digit8", label: "8" }, { code: "Digit9", label: "9" },
  { code: "Digit0", label: "0" }, { code: "Minus", label: "-" }, { code: "Equal", label: "=" },
];
const NUMPAD = { Numpad1: 0, Numpad2: 1, Numpad3: 2, Numpad4: 3, Numpad5: 4, Numpad6: 5, Numpad7: 6, Numpad8: 7,
                 Numpad9: 8, Numpad0: 9 };

/** The index (0-based) of the task key of a keyboard event in TASK_KEYS, or null when it is not one. */
export function taskKeyIndex(event) {
  if (event.ctrlKey || event.altKey || event.metaKey || event.shiftKey) return null;
  const index = TASK_KEYS.findIndex((k) => k.code === event.code);
  if (index >= 0) return index;
  return event.code in NUMPAD ? NUMPAD[event.code] : null;
}

/** A key that types a character (a letter, digit or sign) without Ctrl, Alt or Meta: not Tab, Enter, F5, … */
function isPlainCharacter(event) {
  return !event.ctrlKey && !event.altKey && !event.metaKey && typeof event.key === "string" && event.key.length === 1;
}

function typing(target) {
  if (!(target instanceof Element)) return false;
  return Boolean(target.closest("input, textarea, select, [contenteditable=''], [contenteditable='true']"));
}

/**
 * Listen for game keys on `target` (the document) and call `onInterrupt(action, event)`, or `onTask(index)`
 * for a task key (not repeated while held). With `repeat` (the fixed clock) a held key repeats at most once per
 * `repeatMs` (one world tick), so the server's queue of three interrupts is not flooded; without it (the paper's
 * clock, where each action steps the world once) a held key is one press. Returns a function that removes the
 * listeners.
 */
export function listenKeys(target, onInterrupt,
                           { repeat = true, repeatMs = 200, onTask = null, onOtherKey = null } = {}) {
  let lastSent = -Infinity;
  let swallowSpaceUp = false;
  const down = (event) => {
    if (typing(event.target)) return;
    const task = onTask ? taskKeyIndex(event) : null;
    if (task !== null) {
      event.preventDefault();
      if (!event.repeat) onTask(task);
      return;
    }
    const action = interruptForKey(event);
    if (!action) {
      if (onOtherKey && !event.repeat && isPlainCharacter(event)) onOtherKey(event.key);
      return;
    }
    event.preventDefault();
    if (action === "interact") swallowSpaceUp = true;
    const now = performance.now();
    if (event.repeat && (!repeat || now - lastSent < repeatMs)) return;
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
