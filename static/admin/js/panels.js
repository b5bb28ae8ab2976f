/**
 * The side panels of the live view and the replay: the modelled knowledge base against the world with
 * its gap components, the robot's belief over the participant's subtask next to the subtask the
 * participant actually has, the robot's decision, and timing (tick lateness, decision time).
 */

import { h } from "../../js/dom.js";
import { heldLabel, subtaskLabel } from "../../js/labels.js";
import { ms } from "./ui.js";

const COMPONENTS = [["grill", "Grill"], ["board", "Board"], ["sink", "Sink"], ["robot_held", "Robot holds"]];

function statusText(value) {
  if (Array.isArray(value)) return value.length ? value.join(", ") : "–";
  return value === null || value === undefined ? "nothing" : heldLabel(value);
}

/** KB vs world per gap component (docs/domain.md §3: 1 where the participant's model differs from the world). */
export function gapPanel(kbSummary, worldSummary, gap, total) {
  const rows = COMPONENTS.map(([key, label]) => {
    const differs = gap && gap[key] === 1;
    return h("tr", { class: differs ? "gap" : "", dataset: { component: key, gap: String(gap ? gap[key] : "") } },
      h("th", { scope: "row" }, label),
      h("td", {}, worldSummary ? statusText(worldSummary[key]) : "–"),
      h("td", {}, kbSummary ? statusText(kbSummary[key]) : "–"),
      h("td", { class: "num" }, differs ? h("strong", {}, "1 ✗") : "0"));
  });
  return h("section", { class: "panel", id: "gap-panel", "aria-label": "Modelled knowledge and its gap" },
    h("h3", {}, "Modelled knowledge vs world ", h("span", { class: "muted", id: "gap-total" }, `gap ${total ?? "–"}`)),
    h("table", { class: "data compact" },
      h("thead", {}, h("tr", {}, h("th", {}, ""), h("th", { scope: "col" }, "World"), h("th", { scope: "col" }, "Participant's model"),
        h("th", { scope: "col" }, "Gap"))),
      h("tbody", {}, rows)));
}

function bar(p) {
  const fill = h("span", {});
  fill.style.width = `${Math.round(p * 1000) / 10}%`;
  return fill;
}

/** The robot's belief over the participant's subtask, highest first; the actual subtask is marked. */
export function beliefPanel(decision, actual) {
  const belief = decision && decision.belief ? Object.entries(decision.belief) : [];
  belief.sort((a, b) => b[1] - a[1]);
  const body = belief.length
    ? h("ol", { class: "belief", id: "belief-list" }, belief.map(([subtask, p]) => h("li",
      { class: subtask === actual ? "actual" : "", dataset: { subtask } },
      h("span", { class: "belief-name" }, subtaskLabel(subtask), subtask === actual ? h("span", { class: "badge" }, "actual") : null),
      h("span", { class: "belief-bar", "aria-hidden": "true" }, bar(p)),
      h("span", { class: "num" }, `${(p * 100).toFixed(1)} %`))))
    : h("p", { class: "muted", id: "belief-list" },
      decision ? "This robot keeps no belief over the participant's subtask." : "No decision yet.");
  return h("section", { class: "panel", id: "belief-panel", "aria-label": "The robot's belief" },
    h("h3", {}, "Robot's belief over the participant's subtask"),
    h("p", { class: "muted" }, "Participant's subtask: ", h("strong", { id: "actual-subtask" }, actual ? subtaskLabel(actual) : "none")),
    body);
}

export function decisionPanel(decision, extra = []) {
  const q = decision && decision.q_values ? Object.entries(decision.q_values).sort((a, b) => b[1] - a[1]) : [];
  return h("section", { class: "panel", id: "decision-panel", "aria-label": "The robot's decision" },
    h("h3", {}, "Robot's decision"),
    h("dl", { class: "facts" },
      h("dt", {}, "Action"), h("dd", { id: "robot-action" }, decision ? decision.action : "–"),
      h("dt", {}, "Planner time"), h("dd", {}, decision ? ms(decision.elapsed_ms) : "–"),
      h("dt", {}, "Explored KBs"), h("dd", {}, decision ? String(decision.explored_kbs) : "–"),
      decision && decision.timed_out ? [h("dt", {}, "Timed out"), h("dd", {}, "yes")] : null,
      ...extra),
    q.length ? h("p", { class: "muted qvalues" }, "Q: ", q.map(([a, v]) => `${a} ${v}`).join(" · ")) : null);
}

export function facts(id, label, pairs) {
  return h("section", { class: "panel", id, "aria-label": label }, h("h3", {}, label),
    h("dl", { class: "facts" }, pairs.map(([term, value, valueId]) => [h("dt", {}, term), h("dd", { id: valueId }, value)])));
}
