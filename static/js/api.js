/**
 * The participant REST API (server/routes/participant.py). Every call after join carries the
 * participant's token as a bearer header; failures raise `ApiError` with the server's typed detail.
 */

export class ApiError extends Error {
  constructor(status, detail) {
    const message = detail && typeof detail === "object" && !Array.isArray(detail) ? detail.message : undefined;
    super(message || `request failed with status ${status}`);
    this.status = status;
    this.detail = detail;
    this.code = detail && typeof detail === "object" && !Array.isArray(detail) ? detail.code : undefined;
  }
}

export class Api {
  constructor(token = "") {
    this.token = token;
  }

  async request(method, path, body) {
    const headers = { Accept: "application/json" };
    if (this.token) headers.Authorization = `Bearer ${this.token}`;
    if (body !== undefined) headers["Content-Type"] = "application/json";
    let response;
    try {
      response = await fetch(path, { method, headers, body: body === undefined ? undefined : JSON.stringify(body),
                                     cache: "no-store" });
    } catch (exc) {
      throw new ApiError(0, { code: "network", message: "The server could not be reached." });
    }
    let data = null;
    try {
      data = await response.json();
    } catch {
      data = null;
    }
    if (!response.ok) throw new ApiError(response.status, data ? data.detail : null);
    return data;
  }

  study(studyId) { return this.request("GET", `/api/studies/${encodeURIComponent(studyId)}`); }
  /**
   * `testLink`: the code of an experimenter's test-run link (`#test=…`), or "" for a participant; `handoff`: the
   * code another device showed, to continue its session here (or "").
   */
  join(studyId, recruiting, testLink, handoff) {
    const body = { recruiting };
    if (testLink) body.test_link = testLink;
    if (handoff) body.handoff = handoff;
    return this.request("POST", `/api/studies/${encodeURIComponent(studyId)}/join`, body);
  }
  resume(studyId, code) {
    return this.request("POST", `/api/studies/${encodeURIComponent(studyId)}/resume`, { code });
  }
  session() { return this.request("GET", "/api/session"); }
  device(info) { return this.request("POST", "/api/session/device", info); }
  consent(accept) { return this.request("POST", "/api/session/consent", { accept }); }
  instructionsDone() { return this.request("POST", "/api/session/instructions_done"); }
  quiz(answers) { return this.request("POST", "/api/session/quiz", { answers }); }
  questionnaire(questionnaireId, answers) {
    return this.request("POST", "/api/session/questionnaire", { questionnaire_id: questionnaireId, answers });
  }
}
