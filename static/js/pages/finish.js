/**
 * The end page, for participants who finished (`done`) and for those screened out (`screened_out`: they
 * declined consent, did not pass the comprehension quiz, or did not take part in a round — told which rule, with
 * what was measured, never a sentence that is not true of them): thanks, the study's code (with a copy button)
 * and, when the study configures one,
 * the redirect back to the recruiting platform after a short countdown (with a link to go at once). A study whose
 * code is still the shipped placeholder gives a real participant no code (`completion.not_set_up`): the page says
 * the study is not set up for payment yet and to contact the researcher (server/flow/payment.py).
 */

import { h, show } from "../dom.js";

export const REDIRECT_SECONDS = 5;

const SCREENED_OUT = {
  declined_consent: "You chose not to take part, so the study ends here. No game data were recorded.",
  server_full: "The study's server was too busy to start your round in time, so the study ends here. We are " +
    "sorry: please return the study with the code below (or contact the researcher), and come back later if " +
    "the study is still open.",
  abandoned_rounds: "The connection to a round was lost for longer than the study allows, so the study ends here " +
    "and it cannot give you the completion code. If something went wrong on your side, please contact the researcher.",
  low_engagement: "A round was played without taking part in it, so the study ends here and it cannot give you " +
    "the completion code. If something went wrong on your side, please contact the researcher.",
  failed_quiz: "The answers to the questions about the instructions were not all right after the attempts this " +
    "study allows, so the study ends here. No game data were recorded. Thank you for your time.",
};

const ENDS = " The study ends here and it cannot give you the completion code. If something went wrong on your " +
  "side, please contact the researcher.";

/** Why a round did not count, in words, from the server's `completion.detail` (its rule, the measured value, the
 * study's limit and the round): each rule its own true sentence (server/flow/engagement.py). */
export const NOT_TAKING_PART = {
  no_actions: (d) => `In round ${d.round} you did not choose a task or press a key, so that round cannot count.`,
  idle: (d) => `In round ${d.round} your cook stood with nothing to do for ${Number(d.value).toFixed(1)} % of ` +
    `the round (this study allows at most ${d.limit} %), so that round cannot count.`,
  task_steps: (d) => `In round ${d.round} the robot did almost all of the work: your cook did ` +
    `${Number(d.value).toFixed(1)} % of the team's steps (this study asks for at least ${d.limit} %), so that round ` +
    "cannot count.",
  refused_tasks: (d) => `By round ${d.round}, ${Number(d.value).toFixed(1)} % of the tasks you chose could not ` +
    `work (this study allows at most ${d.limit} %): they were chosen without looking at the kitchen, so that round ` +
    "cannot count.",
};

/** The end page's sentence for a participant who was screened out. */
export function screenedOutText(completion) {
  const detail = completion.detail;
  if (completion.reason === "low_engagement" && detail && NOT_TAKING_PART[detail.rule]) {
    return NOT_TAKING_PART[detail.rule](detail) + ENDS;
  }
  return SCREENED_OUT[completion.reason] || SCREENED_OUT.declined_consent;
}

export function finishPage(root, ctx) {
  const { session } = ctx;
  const completion = session.completion || {};
  const finished = session.state === "done";
  const title = h("h1", { id: "finish-title", tabindex: "-1" },
    finished ? "Thank you — you have finished the study" : "Thank you for your interest");
  const parts = [title];
  parts.push(h("p", { id: "finish-text" }, finished ? "Your answers and games have been saved."
    : screenedOutText(completion)));

  if (completion.not_set_up) {
    parts.push(h("div", { id: "not-set-up", class: "page-notice", role: "status" },
      h("p", {}, "This study is not set up for payment yet, so there is no code to show. Please contact the " +
        "researcher and quote your participant number:"),
      h("p", {}, h("code", { class: "participant-number", id: "participant-number" }, session.participant_id))));
  }
  if (completion.code) {
    const code = h("output", { class: "code", id: "completion-code" }, completion.code);
    const status = h("span", { class: "muted", role: "status" });
    const copy = h("button", { type: "button", class: "secondary", id: "copy-code", onclick: async () => {
      try {
        await navigator.clipboard.writeText(completion.code);
        status.textContent = "Copied.";
      } catch {
        status.textContent = "Select the code and copy it by hand.";
      }
    } }, "Copy code");
    parts.push(h("p", {}, finished ? "Your completion code:" : "Your code:"),
               h("div", { class: "code-row" }, code, copy, status));
  }

  let timer = 0;
  if (completion.redirect_url) {
    let left = REDIRECT_SECONDS;
    const count = h("span", { id: "redirect-seconds" }, String(left));
    const link = h("a", { href: completion.redirect_url, id: "redirect-link", rel: "noreferrer" }, "Go now");
    parts.push(h("p", { id: "redirect-note" }, "You will be taken back to the recruiting site in ", count,
      " seconds. ", link));
    timer = window.setInterval(() => {
      left -= 1;
      count.textContent = String(Math.max(left, 0));
      if (left <= 0) {
        window.clearInterval(timer);
        window.location.assign(completion.redirect_url);
      }
    }, 1000);
  } else {
    parts.push(h("p", { class: "muted" }, completion.code
      ? "Enter this code on the recruiting site, then you can close this window."
      : "You can close this window now."));
  }

  show(root, h("section", { class: "card narrow", id: "finish", dataset: { kind: completion.kind || "" },
                            "aria-labelledby": "finish-title" }, parts), title);
  return () => window.clearInterval(timer);
}
