/**
 * A questionnaire (session.questionnaire): one rating scale per item, as native radio buttons in a
 * fieldset, so it works with the keyboard (Tab between items, arrow keys along a scale) and screen
 * readers. Required items must be answered: missing ones are marked and focused, and the server's own
 * check (422 with one problem per item) is shown the same way. Answers survive a refresh (sessionStorage).
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
  const legendId = `${name}-legend`;
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
  const fieldset = h("fieldset", { class: "item", id: name, "aria-describedby": `${name}-error`, dataset: { item: item.id } },
    h("legend", { id: legendId }, h("span", { class: "item-number" }, `${index + 1}.`), " ", item.text,
      item.required ? null : h("span", { class: "optional" }, " (optional)")),
    h("div", { class: "scale", style: `--points: ${points.length}` }, points),
    problem);
  return { fieldset, problem };
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
  };
  q.items.forEach((item, i) => items.set(item.id, scaleItem(item, i, answers[item.id], onChange)));

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
      const radio = first.querySelector("input");
      if (radio) radio.focus({ preventScroll: true });
    }
    return first !== null;
  };

  const submit = h("button", { type: "submit", class: "primary", id: "questionnaire-submit" }, "Continue");
  const form = h("form", { class: "questionnaire", novalidate: true },
    [...items.values()].map((e) => e.fieldset), h("div", { class: "actions" }, submit), error);
  form.addEventListener("submit", async (event) => {
    event.preventDefault();
    error.textContent = "";
    const missing = q.items.filter((i) => i.required && answers[i.id] === undefined)
      .map((i) => [i.id, "Please answer this question."]);
    if (markProblems(missing)) {
      error.textContent = `Please answer ${missing.length === 1 ? "the marked question" : `the ${missing.length} marked questions`}.`;
      return;
    }
    submit.disabled = true;
    const body = {};
    for (const item of q.items) if (answers[item.id] !== undefined) body[item.id] = answers[item.id];
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
