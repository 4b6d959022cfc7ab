// The service's HTTP API as the page uses it. URLs are relative to the page, so the page works
// behind a path prefix too. Requests carry the tab's API key, if one is kept (key.js).

import { authorization } from "./key.js";

/** An answer that is not a 2xx: an RFC 9457 problem (or a stand-in for a non-problem body). */
export class ProblemError extends Error {
  constructor(status, problem) {
    super(problem.detail || problem.title || `HTTP ${status}`);
    this.status = status;
    this.problem = problem;
  }
}

async function postJSON(path, body, { signal } = {}) {
  let response;
  try {
    response = await fetch(new URL(path, document.baseURI), {
      method: "POST",
      headers: {
        "content-type": "application/json",
        accept: "application/json, application/problem+json",
        ...authorization(),
      },
      body: JSON.stringify(body),
      signal,
    });
  } catch (error) {
    if (error.name === "AbortError") throw error;
    throw new ProblemError(0, {
      title: "The service cannot be reached",
      detail: `${error.message}. Is the server still running?`,
    });
  }
  const text = await response.text();
  let data;
  try {
    data = JSON.parse(text);
  } catch {
    data = { title: response.statusText, detail: text.slice(0, 300) };
  }
  if (!response.ok) {
    const retry = response.headers.get("retry-after");
    throw new ProblemError(response.status, { status: response.status, ...data, retryAfter: retry });
  }
  return data;
}

/** POST /solve: one equilibrium. */
export function solve(request, options) {
  return postJSON("solve", request, options);
}

/**
 * A sweep over airspeeds, reporting progress through `onProgress({done, total, message})`.
 *
 * Today this is one POST /sweep: progress is reported at the start ({done: 0, total}) and the end
 * ({done: total}), and the page shows an indeterminate busy state in between. This function is the
 * seam for long work: when the API gains jobs (POST /jobs answering with the job's URL, progress
 * as server-sent events), only its body changes, e.g.
 *
 *     const job = await postJSON("jobs", { kind: "sweep", request }, { signal });
 *     const events = new EventSource(new URL(job.events, document.baseURI));
 *     events.addEventListener("progress", (e) => onProgress(JSON.parse(e.data)));
 *     ... resolve with the "done" event's result, close `events` on abort ...
 *
 * and the page already draws a determinate bar from `done` and `total`. Cancelling aborts `signal`.
 */
export async function runSweep(request, { signal, onProgress } = {}) {
  const total = request.velocities?.count ?? request.velocities?.length ?? 0;
  onProgress?.({ done: 0, total, message: `Solving ${total} airspeeds and tracing the fold` });
  const result = await postJSON("sweep", request, { signal });
  onProgress?.({ done: total, total, message: "Done" });
  return result;
}

/** The running server's OpenAPI document (which fields this API version has), or null. */
export async function openapi() {
  try {
    const response = await fetch(new URL("openapi.json", document.baseURI));
    return response.ok ? await response.json() : null;
  } catch {
    return null;
  }
}
