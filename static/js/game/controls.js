/**
 * The participant's controls: one button per subtask of the protocol's `hello.subtasks` (always all of
 * them, so the buttons reveal nothing that is out of view) and one per interrupt action, labelled with its
 * keys. The task being done is highlighted (aria-pressed).
 *
 * A task that cannot work with what the cook holds (`hello.needs`; what the cook holds is always known to
 * the participant, so this reveals nothing) is disabled with its reason: `aria-disabled` and
 * `aria-describedby` for screen readers, the reason as a tooltip on hover and in the "why" line under the
 * tasks on hover and keyboard focus. Choosing it anyway only shows the reason. While offline every button
 * is marked aria-disabled rather than disabled, so keyboard focus stays where the participant left it.
 *
 * Task keys: the tasks a dish needs, in the order shown, carry the number-row keys 1–9, 0, -, = (game/keys.js
 * TASK_KEYS), shown on the button; "Put on counter" has none (a dish never needs it). A task key acts like a
 * click on its button.
 */

import { h } from "../dom.js";
import { INTERRUPTS, SUBTASK_GROUPS, SUBTASKS, subtaskLabel } from "../labels.js";
import { handsReason } from "./reasons.js";
import { TASK_KEYS } from "./keys.js";

/** Tasks without a key: the number row has twelve keys and a dish needs twelve tasks, not this one. */
const UNKEYED = new Set(["drop_on_counter"]);

export class Controls {
  /** `onRefused(subtask, reason)`: a disabled task was chosen; `labels`: interrupt id → label replacing the usual
   * one (the first-person view's "Forward", …). */
  constructor({ subtasks, interrupts, needs = {}, onSelect, onInterrupt, onRefused = () => {}, labels = {} }) {
    this.enabled = false;
    this.buttons = new Map();
    this.reasons = new Map();
    this.needs = needs;
    this.current = null;
    this.held = undefined;
    const known = new Set(subtasks);
    const grouped = SUBTASK_GROUPS.map((g) => ({ ...g, subtasks: g.subtasks.filter((s) => known.has(s)) }));
    const listed = new Set(grouped.flatMap((g) => g.subtasks));
    const others = subtasks.filter((s) => !listed.has(s));
    if (others.length) grouped.push({ title: "Other", subtasks: others });

    this.why = h("p", { class: "task-why", id: "task-why", "aria-live": "polite" });
    this.descriptions = h("div", { class: "visually-hidden" });
    this.keyed = grouped.flatMap((g) => g.subtasks).filter((s) => !UNKEYED.has(s)).slice(0, TASK_KEYS.length);
    this.choose = (id) => {
      if (!this.enabled) return;
      const why = this.reasons.get(id);
      if (why) onRefused(id, why);
      else onSelect(id);
    };
    const taskButton = (id) => {
      this.descriptions.append(h("span", { id: `why-${id}` }));
      const key = TASK_KEYS[this.keyed.indexOf(id)];
      const button = h("button", {
        type: "button", class: "task-button", "aria-pressed": "false", title: (SUBTASKS[id] || {}).hint,
        dataset: { subtask: id, key: key ? key.label : "" }, "aria-keyshortcuts": key ? key.label : null,
        onclick: () => this.choose(id),
        onfocus: () => this.explain(id), onmouseenter: () => this.explain(id),
        onblur: () => this.explain(null), onmouseleave: () => this.explain(null),
      }, key ? h("kbd", { class: "task-key", "aria-hidden": "true" }, key.label) : null, subtaskLabel(id));
      this.buttons.set(id, button);
      return button;
    };
    this.tasks = h("nav", { class: "tasks", "aria-label": "Tasks" },
      h("h2", { class: "panel-title" }, "Choose a task"),
      grouped.filter((g) => g.subtasks.length).map((g) => h("section", { class: "task-group" },
        h("h3", {}, g.title), h("div", { class: "task-grid" }, g.subtasks.map(taskButton)))),
      this.why, this.descriptions);

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

  /** A task key was pressed (`index` in TASK_KEYS): as a click on its task's button; false when it has none. */
  chooseKey(index) {
    const id = this.keyed[index];
    if (!id) return false;
    this.choose(id);
    return true;
  }

  setEnabled(enabled) {
    this.enabled = enabled;
    this.refresh();
  }

  /** What the cook holds now: tasks that cannot work with it are disabled with their reason. */
  setHeld(held) {
    const now = held || null;
    if (now === this.held) return;
    this.held = now;
    this.reasons.clear();
    for (const id of this.buttons.keys()) {
      const reason = handsReason(this.needs[id], now);
      if (reason) this.reasons.set(id, reason);
    }
    this.refresh();
  }

  refresh() {
    for (const [id, button] of this.buttons) {
      const reason = this.reasons.get(id) || null;
      const off = !this.enabled || reason !== null;
      button.setAttribute("aria-disabled", String(off));
      button.classList.toggle("unfit", reason !== null);
      button.title = reason || (SUBTASKS[id] || {}).hint || "";
      const described = this.descriptions.querySelector(`#why-${id}`);
      if (described) described.textContent = reason ? `Not possible now: ${reason}.` : "";
      if (reason) button.setAttribute("aria-describedby", `why-${id}`);
      else button.removeAttribute("aria-describedby");
    }
    for (const b of this.interruptButtons) b.setAttribute("aria-disabled", String(!this.enabled));
    if (this.explaining) this.explain(this.explaining);
  }

  /** Show why task `id` is disabled in the line under the tasks (hover and focus); `null` clears it. */
  explain(id) {
    this.explaining = id;
    const reason = id ? this.reasons.get(id) : null;
    const text = reason ? `${subtaskLabel(id)}: ${reason}.` : "";
    if (this.why.textContent !== text) this.why.textContent = text;
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
