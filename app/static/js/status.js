// The run status under "Results": busy (progress bar, elapsed time, Cancel for a job) or idle
// with its last words. While busy every run button (button[data-operation]) is disabled.

import { $ } from "./dom.js";
import { state } from "./state.js";

let ticker = null;

function runButtons(disabled) {
  for (const button of document.querySelectorAll("button[data-operation]")) button.disabled = disabled;
}

export function setBusy(message, { cancellable = false } = {}) {
  state.busy = true;
  const started = performance.now();
  $("progress").hidden = false;
  $("progress").removeAttribute("value");
  $("status-text").textContent = message;
  $("cancel").hidden = !cancellable;
  $("results").setAttribute("aria-busy", "true");
  runButtons(true);
  clearInterval(ticker);
  ticker = setInterval(() => {
    $("status-text").dataset.elapsed = `${((performance.now() - started) / 1000).toFixed(1)} s`;
  }, 100);
}

export function setProgress({ done, total, message }) {
  if (total > 0 && done > 0) {
    $("progress").max = total;
    $("progress").value = done;
  }
  if (message) $("status-text").textContent = message;
}

export function setIdle(message) {
  state.busy = false;
  clearInterval(ticker);
  $("progress").hidden = true;
  $("status-text").textContent = message;
  delete $("status-text").dataset.elapsed;
  $("cancel").hidden = true;
  $("results").removeAttribute("aria-busy");
  runButtons(false);
}

export function wireCancel() {
  $("cancel").addEventListener("click", () => state.abort?.abort());
}
