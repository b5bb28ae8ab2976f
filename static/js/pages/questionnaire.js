/**
 * A questionnaire (session.questionnaire): rating items as a scale of native radio buttons, choice items as a
 * list of radio buttons, text items as a text box with its length limits (a counter shows the characters
 * left), each in a fieldset, so it works with the keyboard and screen readers. Required items must be
 * answered: missing or too short ones are marked and focused, and the server's own check (422 with one
 * problem per item) is shown the same way. Answers survive a refresh (sessionStorage).
 */

import { h, show } from "../dom.js";
import { actionError } from "./common.js";

function draftKey(session) {
  return `steakhouse.answers.${session.participant_id}.${session.step}`;
}

function loadDraft(key) {
  try {
    return JSON.parse(window.sessionStorage.getItem(key) || "{}") || {};
  } catch {
    return {};
  }
}

function saveDraft(key, answers) {
  try {
    window.sessionStorage.setItem(key, JSON.stringify(answers));
  } catch {
    /* storage disabled */
  }
}

function scaleItem(item, index, value, onChange) {
  const name = `item-${item.id}`;
  const problem = h("p", { class: "item-error", id: `${name}-error`, role: "alert" });
  const points = [];
  for (let v = item.scale.min; v <= item.scale.max; v += 1) {
    const label = item.scale.labels[String(v)];
    const input = h("input", { type: "radio", name, value: String(v), id: `${name}-${v}`, checked: value === v,
                              onchange: () => onChange(item.id, v) });
    points.push(h("label", { class: "scale-point", for: `${name}-${v}` }, input,
      h("span", { class: "scale-number" }, String(v)),
      h("span", { class: "scale-anchor" }, label || "")));
  }
  const scale = h("div", { class: "scale", style: `--points: ${points.length}` }, points);
  return { fieldset: itemFrame(item, index, name, scale, problem), problem };
}

function itemFrame(item, index, name, body, problem) {
  return h("fieldset", { class: `item item-${item.type || "rating"}`, id: name, "aria-describedby": `${name}-error`,
                         dataset: { item: item.id } },
    h("legend", { id: `${name}-legend` }, h("span", { class: "item-number" }, `${index + 1}.`), " ", item.text,
      item.required ? null : h("span", { class: "optional" }, " (optional)")),
    body, problem);
}

function choiceItem(item, index, value, onChange) {
  const name = `item-${item.id}`;
  const problem = h("p", { class: "item-error", id: `${name}-error`, role: "alert" });
  const options = item.options.map((text, i) => h("label", { class: "choice-option", for: `${name}-${i}` },
    h("input", { type: "radio", name, value: String(i), id: `${name}-${i}`, checked: value === i,
                 onchange: () => onChange(item.id, i) }),
    h("span", {}, text)));
  return { fieldset: itemFrame(item, index, name, h("div", { class: "choices" }, options), problem), problem };
}

function textItem(item, index, value, onChange) {
  const name = `item-${item.id}`;
  const problem = h("p", { class: "item-error", id: `${name}-error`, role: "alert" });
  const count = h("span", { class: "text-count", id: `${name}-count`, "aria-live": "polite" });
  const box = h("textarea", { id: `${name}-text`, name, rows: "3", maxlength: String(item.max_length),
                              "aria-labelledby": `${name}-legend`, "aria-describedby": `${name}-count` });
  box.value = typeof value === "string" ? value : "";
  const counted = () => {
    const left = item.max_length - box.value.length;
    const least = item.min_length ? `At least ${item.min_length} characters. ` : "";
    count.textContent = `${least}${left} character${left === 1 ? "" : "s"} left.`;
  };
  box.addEventListener("input", () => {
    counted();
    onChange(item.id, box.value);
  });
  counted();
  return { fieldset: itemFrame(item, index, name, h("div", { class: "text-answer" }, box, count), problem), problem };
}

const ITEM = { rating: scaleItem, choice: choiceItem, text: textItem };

/** The answer to send for an item (text trimmed; an empty text is no answer), or undefined. */
function answerOf(item, value) {
  if (value === undefined || value === null) return undefined;
  if (item.type === "text") return value.trim() ? value.trim() : undefined;
  return value;
}

/** Why an answer cannot be sent yet (a required item unanswered, a text too short), or null. */
function problemOf(item, value) {
  const answer = answerOf(item, value);
  if (answer === undefined) return item.required ? "Please answer this question." : null;
  if (item.type === "text" && item.min_length && answer.length < item.min_length) {
    return `Please write at least ${item.min_length} characters.`;
  }
  return null;
}

export function questionnairePage(root, ctx) {
  const { session } = ctx;
  const q = session.questionnaire;
  const key = draftKey(session);
  const answers = loadDraft(key);
  const items = new Map();
  const error = h("p", { class: "error", role: "alert", id: "questionnaire-error" });
  const onChange = (id, v) => {
    answers[id] = v;
    saveDraft(key, answers);
    const entry = items.get(id);
    entry.problem.textContent = "";
    entry.fieldset.classList.remove("invalid");
    if (![...items.values()].some((e) => e.fieldset.classList.contains("invalid"))) error.textContent = "";
  };
  q.items.forEach((item, i) => items.set(item.id, (ITEM[item.type] || scaleItem)(item, i, answers[item.id], onChange)));

  const markProblems = (problems) => {
    let first = null;
    for (const [id, text] of problems) {
      const entry = items.get(id);
      if (!entry) continue;
      entry.problem.textContent = text;
      entry.fieldset.classList.add("invalid");
      first = first || entry.fieldset;
    }
    if (first) {
      first.scrollIntoView({ block: "center" });
      const control = first.querySelector("input, textarea");
      if (control) control.focus({ preventScroll: true });
    }
    return first !== null;
  };

  const submit = h("button", { type: "submit", class: "primary", id: "questionnaire-submit" }, "Continue");
  const form = h("form", { class: "questionnaire", novalidate: true },
    [...items.values()].map((e) => e.fieldset), h("div", { class: "actions" }, submit), error);
  form.addEventListener("submit", async (event) => {
    event.preventDefault();
    error.textContent = "";
    const missing = q.items.map((i) => [i.id, problemOf(i, answers[i.id])]).filter(([, why]) => why);
    if (markProblems(missing)) {
      error.textContent = `Please check ${missing.length === 1 ? "the marked question" : `the ${missing.length} marked questions`}.`;
      return;
    }
    submit.disabled = true;
    const body = {};
    for (const item of q.items) {
      const answer = answerOf(item, answers[item.id]);
      if (answer !== undefined) body[item.id] = answer;
    }
    try {
      const next = await ctx.api.questionnaire(q.id, body);
      try { window.sessionStorage.removeItem(key); } catch { /* storage disabled */ }
      ctx.route(next);
    } catch (exc) {
      submit.disabled = false;
      if (exc.status === 422 && Array.isArray(exc.detail)) {
        markProblems(exc.detail.map((p) => [p.loc[p.loc.length - 1], p.msg]));
        error.textContent = "Please check the marked questions.";
      } else {
        actionError(exc, error, ctx);
      }
    }
  });

  const intro = q.after_trial === null || q.after_trial === undefined
    ? "A few last questions about the study."
    : "Please answer these questions about the round you just played.";
  const title = h("h1", { id: "questionnaire-title", tabindex: "-1" }, q.title || "Questions");
  show(root, h("section", { class: "card prose", id: "questionnaire", "aria-labelledby": "questionnaire-title" },
    title,
    h("p", {}, intro, " Questions not marked optional need an answer."),
    form), title);
}
