/**
 * The participant's controls: one button per subtask of the protocol's `hello.subtasks` (always all of
 * them, whatever the world looks like, so the buttons reveal nothing that is out of view) and one per
 * interrupt action, labelled with its keys. The task being done is highlighted (aria-pressed).
 *
 * While offline the buttons are marked aria-disabled rather than disabled, so keyboard focus stays
 * where the participant left it.
 */

import { h } from "../dom.js";
import { INTERRUPTS, SUBTASK_GROUPS, SUBTASKS, subtaskLabel } from "../labels.js";

export class Controls {
  /** `labels`: interrupt id → label replacing the usual one (the first-person view's "Forward", …). */
  constructor({ subtasks, interrupts, onSelect, onInterrupt, labels = {} }) {
    this.enabled = false;
    this.buttons = new Map();
    this.current = null;
    const known = new Set(subtasks);
    const grouped = SUBTASK_GROUPS.map((g) => ({ ...g, subtasks: g.subtasks.filter((s) => known.has(s)) }));
    const listed = new Set(grouped.flatMap((g) => g.subtasks));
    const others = subtasks.filter((s) => !listed.has(s));
    if (others.length) grouped.push({ title: "Other", subtasks: others });

    const taskButton = (id) => {
      const button = h("button", {
        type: "button", class: "task-button", "aria-pressed": "false", title: (SUBTASKS[id] || {}).hint,
        dataset: { subtask: id },
        onclick: () => this.enabled && onSelect(id),
      }, subtaskLabel(id));
      this.buttons.set(id, button);
      return button;
    };
    this.tasks = h("nav", { class: "tasks", "aria-label": "Tasks" },
      h("h2", { class: "panel-title" }, "Choose a task"),
      grouped.filter((g) => g.subtasks.length).map((g) => h("section", { class: "task-group" },
        h("h3", {}, g.title), h("div", { class: "task-grid" }, g.subtasks.map(taskButton)))));

    const allowed = new Set(interrupts);
    this.interruptButtons = INTERRUPTS.filter((i) => allowed.has(i.id)).map((i) => h("button", {
      type: "button", class: `interrupt-button interrupt-${i.id}`, dataset: { interrupt: i.id },
      "aria-keyshortcuts": i.keys.map(ariaKey).join(" "),
      onclick: () => this.enabled && onInterrupt(i.id),
    }, h("span", { class: "interrupt-label" }, labels[i.id] || i.label),
       h("span", { class: "keys" }, i.keys.map((k) => h("kbd", {}, k)))));
    this.interrupts = h("div", { class: "interrupts", role: "group", "aria-label": "Interrupt actions" },
      this.interruptButtons);
    this.setEnabled(false);
  }

  setEnabled(enabled) {
    this.enabled = enabled;
    for (const b of [...this.buttons.values(), ...this.interruptButtons]) b.setAttribute("aria-disabled", String(!enabled));
  }

  /** Highlight `subtask` (or nothing); `pending` marks a choice sent but not yet confirmed. */
  setCurrent(subtask, pending = false) {
    if (this.current === subtask && !pending && !this.pending) return;
    this.current = subtask;
    this.pending = pending;
    for (const [id, button] of this.buttons) {
      const on = id === subtask;
      button.setAttribute("aria-pressed", String(on));
      button.classList.toggle("pending", on && pending);
    }
  }

  /** Flash an interrupt button briefly so a key press is visibly acknowledged. */
  flash(action) {
    const button = this.interruptButtons.find((b) => b.dataset.interrupt === action);
    if (!button) return;
    button.classList.remove("flash");
    void button.offsetWidth;
    button.classList.add("flash");
  }
}

function ariaKey(label) {
  return { "↑": "ArrowUp", "↓": "ArrowDown", "←": "ArrowLeft", "→": "ArrowRight", Esc: "Escape", Space: "Space" }[label] || label;
}
