/**
 * The comprehension quiz (session.quiz): one group of radio buttons per question, every one to be answered
 * correctly before the practice starts. A wrong answer shows its explanation beside the question and the
 * participant tries again (their choices stay, so only the wrong ones need changing); the number of attempts
 * left is shown after a failed one. After the study's last allowed attempt the server screens out and the
 * end page follows.
 */

import { h, show } from "../dom.js";
import { actionError } from "./common.js";

function questionBlock(question, index, onChange) {
  const name = `quiz-${question.id}`;
  const explanation = h("p", { class: "item-error quiz-explanation", id: `${name}-explanation`, role: "alert" });
  const options = question.options.map((text, i) => h("label", { class: "choice-option", for: `${name}-${i}` },
    h("input", { type: "radio", name, value: String(i), id: `${name}-${i}`,
                 onchange: () => onChange(question.id, i) }),
    h("span", {}, text)));
  const fieldset = h("fieldset", { class: "item quiz-question", id: name, dataset: { question: question.id },
                                   "aria-describedby": `${name}-explanation` },
    h("legend", {}, h("span", { class: "item-number" }, `${index + 1}.`), " ", question.text),
    h("div", { class: "choices" }, options),
    explanation);
  return { fieldset, explanation };
}

export function quizPage(root, ctx) {
  const quiz = ctx.session.quiz;
  const answers = {};
  const blocks = new Map();
  const error = h("p", { class: "error", role: "alert", id: "quiz-error" });
  const left = h("p", { class: "muted", id: "quiz-attempts" });
  const onChange = (id, value) => {
    answers[id] = value;
    const block = blocks.get(id);
    block.fieldset.classList.remove("invalid");
  };
  quiz.questions.forEach((q, i) => blocks.set(q.id, questionBlock(q, i, onChange)));
  const attemptsLeft = (used) => quiz.max_attempts - used;
  if (quiz.attempts_used > 0) {
    left.textContent = `Attempts left: ${attemptsLeft(quiz.attempts_used)} of ${quiz.max_attempts}.`;
  }

  const submit = h("button", { type: "submit", class: "primary", id: "quiz-submit" }, "Check my answers");
  const form = h("form", { class: "questionnaire quiz", novalidate: true },
    [...blocks.values()].map((b) => b.fieldset), h("div", { class: "actions" }, submit), left, error);
  form.addEventListener("submit", async (event) => {
    event.preventDefault();
    error.textContent = "";
    const missing = quiz.questions.filter((q) => answers[q.id] === undefined);
    if (missing.length) {
      for (const q of missing) blocks.get(q.id).fieldset.classList.add("invalid");
      error.textContent = "Please answer every question.";
      blocks.get(missing[0].id).fieldset.querySelector("input").focus();
      return;
    }
    submit.disabled = true;
    try {
      const view = await ctx.api.quiz(answers);
      const result = view.quiz_result;
      if (view.state !== "quiz") {
        ctx.route(view);
        return;
      }
      submit.disabled = false;
      const wrong = new Map(result.wrong.map((w) => [w.id, w.explanation]));
      for (const [id, block] of blocks) {
        const why = wrong.get(id);
        block.fieldset.classList.toggle("invalid", Boolean(why));
        block.explanation.textContent = why ? `Not quite. ${why}` : "";
      }
      left.textContent = `Attempts left: ${result.attempts_left} of ${quiz.max_attempts}.`;
      error.textContent = wrong.size === 1 ? "One answer is not right yet: read the note and try again."
        : `${wrong.size} answers are not right yet: read the notes and try again.`;
      const first = blocks.get(result.wrong[0].id).fieldset;
      first.scrollIntoView({ block: "center" });
      first.querySelector("input").focus({ preventScroll: true });
    } catch (exc) {
      submit.disabled = false;
      actionError(exc, error, ctx);
    }
  });

  const title = h("h1", { id: "quiz-title", tabindex: "-1" }, "A few questions before you start");
  show(root, h("section", { class: "card prose", id: "quiz", "aria-labelledby": "quiz-title" },
    title,
    h("p", {}, "Check that the instructions are clear: answer every question correctly to go on to the practice. " +
      `You have ${quiz.max_attempts} attempt${quiz.max_attempts === 1 ? "" : "s"}.`),
    form), title);
}
