/**
 * Consent: the study's consent text (Markdown), "I agree" and "I do not agree". Declining asks once
 * more, then ends the session politely with the study's screen-out code or redirect (end page).
 */

import { h, show } from "../dom.js";
import { renderMarkdown } from "../markdown.js";
import { actionError } from "./common.js";

export function consentPage(root, ctx) {
  const error = h("p", { class: "error", role: "alert", id: "consent-error" });
  const agree = h("button", { type: "button", class: "primary", id: "consent-agree" }, "I agree");
  const decline = h("button", { type: "button", class: "secondary", id: "consent-decline" }, "I do not agree");
  const actions = h("div", { class: "actions" }, agree, decline);

  const answer = async (accept) => {
    for (const b of actions.querySelectorAll("button")) b.disabled = true;
    error.textContent = "";
    try {
      ctx.route(await ctx.api.consent(accept));
    } catch (exc) {
      if (!actionError(exc, error, ctx)) for (const b of actions.querySelectorAll("button")) b.disabled = false;
    }
  };
  agree.addEventListener("click", () => answer(true));
  decline.addEventListener("click", () => {
    const confirm = h("button", { type: "button", class: "secondary", id: "consent-decline-confirm",
                                  onclick: () => answer(false) }, "Yes, do not take part");
    const back = h("button", { type: "button", class: "primary", id: "consent-back",
                               onclick: () => { actions.replaceChildren(agree, decline); agree.focus(); } }, "Go back");
    actions.replaceChildren(h("p", { class: "confirm-text" }, "You chose not to take part. The study will end here."),
                            confirm, back);
    confirm.focus();
  });

  show(root, h("section", { class: "card prose", id: "consent", "aria-label": "Consent" },
    renderMarkdown(ctx.session.consent), actions, error));
}
