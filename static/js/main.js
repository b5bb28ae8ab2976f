/**
 * The participant client: reads the link (landing) and checks the device, then shows the page for the
 * participant's state as the server reports it (GET /api/session): consent → instructions → quiz → practice /
 * trial rounds and questionnaires → the end page. The server's state machine is the single source of truth;
 * after every action the page is chosen again from the state the server answers.
 */

import { h, setProgress } from "./dom.js";
import { enter, readLink } from "./landing.js";
import { deviceInfo, devicePage, deviceRefused } from "./device.js";
import { consentPage } from "./pages/consent.js";
import { instructionsPage } from "./pages/instructions.js";
import { quizPage } from "./pages/quiz.js";
import { trialPage } from "./pages/trial.js";
import { questionnairePage } from "./pages/questionnaire.js";
import { finishPage } from "./pages/finish.js";
import { messagePage } from "./pages/common.js";

const root = document.getElementById("app");
const PAGES = {
  consent: consentPage,
  instructions: instructionsPage,
  quiz: quizPage,
  practice: trialPage,
  trial: trialPage,
  questionnaire: questionnairePage,
  done: finishPage,
  screened_out: finishPage,
};

let cleanup = null;
let ctx = null;

async function route(session) {
  if (cleanup) cleanup();
  cleanup = null;
  let current = session;
  if (!current) {
    try {
      current = await ctx.api.session();
    } catch (exc) {
      failure(exc);
      return;
    }
  }
  ctx.session = current;
  document.body.dataset.state = current.state;
  const refused = deviceRefused(current);
  setProgress(refused || current.state === "done" || current.state === "screened_out" ? "" :
    `Part ${current.step + 1} of ${current.steps}`);
  if (refused) {
    devicePage(root, ctx);
    return;
  }
  const page = PAGES[current.state];
  if (!page) {
    messagePage(root, "Unexpected state", `The study is in a state this page does not know (${current.state}).`);
    return;
  }
  cleanup = page(root, ctx) || null;
  if (current.notice === "round_ended_away" && !document.body.classList.contains("playing")) {
    root.prepend(h("p", { class: "page-notice", id: "page-notice", role: "status" },
      "Your last round ended while you were away: the connection was lost for longer than the study allows."));
  }
}

function retryButton() {
  return h("button", { type: "button", class: "primary", onclick: () => window.location.reload() }, "Try again");
}

/** The session started on another device whose check refused it: ask for the code that device shows. */
function handoffPage(link, wrong) {
  const input = h("input", { id: "handoff-input", type: "text", autocomplete: "off", spellcheck: "false",
                             "aria-label": "Code shown on your other device", maxlength: "20" });
  const go = h("button", { type: "submit", class: "primary", id: "handoff-go" }, "Continue here");
  const form = h("form", { id: "handoff-form", onsubmit: (event) => {
    event.preventDefault();
    if (!input.value.trim()) return;
    go.disabled = true;
    start({ ...link, handoff: input.value.trim() });
  } }, input, " ", go);
  messagePage(root, "Continue the study on this computer",
    [wrong ? "That is not the code your other device shows. Please check it and type it again."
       : "You started this study on another device. Type the code it shows to continue here:"], form);
  input.focus();
}

function failure(exc, link) {
  if (exc.status === 409 && (exc.code === "handoff_code_required" || exc.code === "handoff_code_wrong")) {
    handoffPage(link, exc.code === "handoff_code_wrong");
  } else if (exc.status === 409 && exc.code === "handoff_locked") {
    messagePage(root, "This session cannot move to this computer",
      "Too many wrong codes were typed. Please contact the researcher: they can send you a link to continue.");
  } else if (exc.status === 409 && exc.code === "already_started") {
    messagePage(root, "This ID has already started in another browser",
      ["Please continue in the browser where you started, or contact the researcher.",
       "For your privacy and the study's, a session can only continue in the browser it started in."]);
  } else if (exc.status === 422 && exc.code === "recruit_id_required") {
    messagePage(root, "This link is incomplete",
      ["Please open the study from its link on the recruiting site: that link carries your participant ID.",
       "If you did, contact the researcher."]);
  } else if (exc.status === 410 && exc.code === "test_link_invalid") {
    messagePage(root, "This test link is no longer valid",
      "Test links work for a limited time. Copy a new one from the admin dashboard (Studies → Recruiting links).");
  } else if (exc.status === 410 && exc.code === "link_invalid") {
    messagePage(root, "This link is no longer valid",
      "Resume links work once and for a limited time. Please contact the researcher for a new one.");
  } else if (exc.status === 404) {
    messagePage(root, "This study is not available", "Please check the link you were given, or contact the researcher.");
  } else if (exc.status === 401) {
    messagePage(root, "Your session was not found", "Please open the link you were given again.", retryButton());
  } else if (exc.status === 0) {
    messagePage(root, "The server could not be reached", "Check your internet connection and try again.", retryButton());
  } else {
    messagePage(root, "Something went wrong", `The study could not be loaded (${exc.message}).`, retryButton());
  }
}

async function boot() {
  const link = readLink();
  if (!link.study) {
    messagePage(root, "This link is incomplete",
      ["The address should name a study, for example /?study=demo.", "Please use the full link you were given."]);
    return;
  }
  if (link.testRun && !link.testLink) {
    messagePage(root, "Test runs start from the admin dashboard",
      ["A test run needs the signed test link of the dashboard (Studies → Recruiting links → Test run).",
       "Participants use the study's participant link."]);
    return;
  }
  await start(link);
}

async function start(link) {
  try {
    const entered = await enter(link);
    ctx = { api: entered.api, link, route, session: entered.session };
    await route(await entered.api.device(deviceInfo()));
  } catch (exc) {
    failure(exc, link);
  }
}

boot();
