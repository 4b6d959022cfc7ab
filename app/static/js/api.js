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

async function call(method, path, { body, signal } = {}) {
  let response;
  try {
    response = await fetch(new URL(path, document.baseURI), {
      method,
      headers: {
        ...(body === undefined ? {} : { "content-type": "application/json" }),
        accept: "application/json, application/problem+json",
        ...authorization(),
      },
      body: body === undefined ? undefined : JSON.stringify(body),
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

function postJSON(path, body, { signal } = {}) {
  return call("POST", path, { body, signal });
}

/** POST /<operation> ("solve", "roll"...), answered at once (a synchronous operation). */
export function answer(operation, request, options) {
  return postJSON(operation, request, options);
}

/** POST /wing/stations: the wing's station values as the solver takes them (N each). */
export function wingStations(wing, options) {
  return postJSON("wing/stations", { wing }, options);
}

/** How often a running job is asked for its state [ms]. */
const POLL_MS = 200;

/** Wait `ms`, or reject as an abort does when `signal` aborts first. */
function pause(ms, signal) {
  return new Promise((resolve, reject) => {
    const aborted = () => {
      clearTimeout(timer);
      reject(new DOMException("The job was cancelled.", "AbortError"));
    };
    const timer = setTimeout(() => {
      signal?.removeEventListener("abort", aborted);
      resolve();
    }, ms);
    signal?.addEventListener("abort", aborted, { once: true });
  });
}

/** Map a job's field paths (`request.wing.chord[2]`) to its body's (`wing.chord[2]`). */
function fromJobRequest(error) {
  const errors = error.problem?.errors;
  if (errors?.length) {
    error.problem.errors = errors.map((e) => ({ ...e, field: String(e.field ?? "").replace(/^request\./, "") }));
  }
  return error;
}

/**
 * An operation as a job ("sweep", "controls", "flutter", "roll", "optimize", "batch"...),
 * reporting progress through `onProgress({done, total, message})`; `unit` names what the
 * progress counts ("airspeeds" unless given: "solves" of a batch).
 *
 * POST /jobs submits `{operation, request}` (a bad body is its 422 here, a full queue its 503:
 * both thrown as `ProblemError`, field paths stripped of `request.` so they name the body's
 * inputs); then GET jobs/{id} every POLL_MS, with the tab's API key (an EventSource could not
 * send it), reporting the job's `progress` until it ends. Resolves with the job's `result`
 * (what POST /<operation> answers); a failed job throws its `problem` (what the operation
 * would have answered) as a `ProblemError`. Aborting `signal` (the page's Cancel) sends DELETE
 * jobs/{id}, best effort, and rejects with an AbortError, as an aborted fetch does.
 */
export async function runJob(operation, request, { signal, onProgress, unit = "airspeeds" } = {}) {
  const count = request.velocities?.count ?? request.velocities?.length ?? request.items?.length ?? 0;
  onProgress?.({ done: 0, total: count, message: count ? `Submitting ${count} ${unit}` : "Submitting" });
  let job;
  try {
    job = await postJSON("jobs", { operation, request }, { signal });
  } catch (error) {
    throw error instanceof ProblemError ? fromJobRequest(error) : error;
  }
  const url = `jobs/${encodeURIComponent(job.id)}`;
  const cancel = () => call("DELETE", url).catch(() => {}); // best effort: the page moves on
  signal?.addEventListener("abort", cancel, { once: true });
  try {
    for (let polls = 0; ; polls++) {
      signal?.throwIfAborted();
      const { done, total } = job.progress ?? { done: 0, total: count };
      if (job.status === "succeeded") {
        onProgress?.({ done: total, total, message: "Done" });
        return job.result;
      }
      if (job.status === "failed") {
        throw fromJobRequest(new ProblemError(job.problem?.status ?? 500, job.problem ?? { title: `The ${operation} failed` }));
      }
      if (job.status === "cancelled") {
        throw new DOMException(`The ${operation} was cancelled.`, "AbortError");
      }
      const doing = job.status === "queued" ? "Queued" : "Solving";
      onProgress?.({ done, total, message: total > 1 ? `${doing}: ${done} of ${total} ${unit}` : doing });
      await pause(polls ? POLL_MS : POLL_MS / 4, signal); // a short sweep is often done at once
      job = await jobState(url, signal);
    }
  } finally {
    signal?.removeEventListener("abort", cancel);
  }
}

/** Refusals of a job's GET (429, 503) waited out in a row before the page gives up. */
const MAX_REFUSALS = 60;

/**
 * GET a running job's state. A rate limit (429) or an overloaded service (503) is waited out for
 * its Retry-After (1 s without one) and asked again: the job runs on regardless, and giving up
 * would lose its answer.
 */
async function jobState(url, signal) {
  for (let refusals = 0; ; refusals++) {
    try {
      return await call("GET", url, { signal });
    } catch (error) {
      const refused = error instanceof ProblemError && (error.status === 429 || error.status === 503);
      if (!refused || refusals >= MAX_REFUSALS) throw error;
      const seconds = Number(error.problem?.retryAfter);
      await pause(1000 * (Number.isFinite(seconds) && seconds > 0 ? seconds : 1), signal);
    }
  }
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
