/**
 * The admin API (server/routes/admin.py) with the bearer token. A 401 from any call means the token is
 * not (or no longer) valid: `onUnauthorized` is called, which forgets it and shows the login form.
 * Downloads go through fetch too (a plain link cannot carry the Authorization header) and are saved
 * from a blob.
 */

export class AdminError extends Error {
  constructor(status, detail) {
    const message = detail && typeof detail === "object" && !Array.isArray(detail) ? detail.message : undefined;
    super(message || (status ? `the server answered ${status}` : "the server could not be reached"));
    this.status = status;
    this.code = detail && typeof detail === "object" && !Array.isArray(detail) ? detail.code : undefined;
  }
}

const enc = encodeURIComponent;

function query(params) {
  const entries = Object.entries(params).filter(([, v]) => v !== undefined && v !== null && v !== "");
  return entries.length ? `?${new URLSearchParams(entries)}` : "";
}

export class AdminApi {
  constructor(token, onUnauthorized = () => {}) {
    this.token = token;
    this.onUnauthorized = onUnauthorized;
  }

  async fetch(method, path, body) {
    const headers = { Authorization: `Bearer ${this.token}` };
    if (body !== undefined) headers["Content-Type"] = "application/json";
    let response;
    try {
      response = await fetch(path, { method, headers, cache: "no-store",
                                     body: body === undefined ? undefined : JSON.stringify(body) });
    } catch {
      throw new AdminError(0, null);
    }
    if (response.status === 401) this.onUnauthorized();
    return response;
  }

  async request(method, path, body) {
    const response = await this.fetch(method, path, body);
    let data = null;
    try {
      data = await response.json();
    } catch {
      data = null;
    }
    if (!response.ok) throw new AdminError(response.status, data ? data.detail : null);
    return data;
  }

  /** Fetch `path` and save it as `filename`; throws AdminError (e.g. status 404) when it is not there. */
  async download(path, filename) {
    const response = await this.fetch("GET", path);
    if (!response.ok) {
      let detail = null;
      try {
        detail = (await response.json()).detail;
      } catch {
        detail = null;
      }
      throw new AdminError(response.status, detail);
    }
    const url = URL.createObjectURL(await response.blob());
    const link = document.createElement("a");
    link.href = url;
    link.download = filename;
    document.body.append(link);
    link.click();
    link.remove();
    window.setTimeout(() => URL.revokeObjectURL(url), 10000);
  }

  studies() { return this.request("GET", "/api/admin/studies"); }
  links(studyId) { return this.request("GET", `/api/admin/studies/${enc(studyId)}/links`); }
  participants(studyId) { return this.request("GET", `/api/admin/participants${query({ study_id: studyId })}`); }
  setFlags(participantId, flags) {
    return this.request("POST", `/api/admin/participants/${enc(participantId)}/flags`, flags);
  }
  /** A one-time, expiring link that moves the participant to a new device: `{path, url, expires_at}`. */
  resumeLink(participantId) {
    return this.request("POST", `/api/admin/participants/${enc(participantId)}/resume_link`);
  }
  answers(participantId) { return this.request("GET", `/api/admin/participants/${enc(participantId)}/answers`); }
  live() { return this.request("GET", "/api/admin/live"); }
  liveTrial(trialId) { return this.request("GET", `/api/admin/live/${enc(trialId)}`); }
  trials(filters) { return this.request("GET", `/api/admin/trials${query(filters)}`); }
  frames(trialId, start, limit) {
    return this.request("GET", `/api/admin/trials/${enc(trialId)}/frames${query({ start, limit })}`);
  }
}

export const exportPath = (studyId) => `/api/admin/studies/${enc(studyId)}/export.zip`;
