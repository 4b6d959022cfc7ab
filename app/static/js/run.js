// How a panel runs its operation, the same for every one: busy (with Cancel and progress for a
// job), its request to the service, a problem next to the fields, or its answer drawn.

import * as api from "./api.js";
import { clearErrors, showProblem } from "./problems.js";
import { state } from "./state.js";
import { setBusy, setIdle, setProgress } from "./status.js";

/** Run `panel`'s operation (registry.js): its request() (null: it said why not), then POST
 * /<operation> (or a job when panel.job), then its render(). Counts the run in state.runs. */
export async function run(panel) {
  if (state.busy) return;
  clearErrors();
  const request = panel.request();
  if (!request) return;
  const words = panel.words(request);
  const controller = panel.job ? new AbortController() : null;
  state.abort = controller;
  setBusy(words.busy, { cancellable: Boolean(controller) });
  let response;
  try {
    response = panel.job
      ? await api.runJob(panel.operation, request, { signal: controller.signal, onProgress: setProgress, unit: panel.unit })
      : await api.answer(panel.operation, request);
  } catch (error) {
    state.runs.failed++;
    if (error.name === "AbortError") {
      setIdle(words.cancelled);
      return;
    }
    setIdle(words.failed);
    if (error instanceof api.ProblemError) showProblem(error, request.flight?.velocity);
    else throw error;
    return;
  } finally {
    state.abort = null;
  }
  panel.last = { request, response };
  state.runs[panel.operation]++;
  setIdle(panel.render(panel.last));
}
