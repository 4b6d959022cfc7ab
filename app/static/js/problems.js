// What went wrong, where the user can fix it: a 422's field errors next to the inputs that
// produced each value, and every problem in plain words in the problem box under "Results".
// Editor modules that generate a value from other inputs (the planform numbers fill the station
// table) add a resolver: addResolver((path) => [controls]).

import { askForKey } from "./key.js";
import { $ } from "./dom.js";

const resolvers = [];

/** `resolve(path)` gives the controls (beyond the one whose data-path is `path`) that made the
 * value at `path` ("wing.chord[3]"), or null to leave it to the others. */
export function addResolver(resolve) {
  resolvers.push(resolve);
}

function describedBy(control, id, add) {
  const ids = new Set((control.getAttribute("aria-describedby") ?? "").split(" ").filter(Boolean));
  if (add) ids.add(id);
  else ids.delete(id);
  if (ids.size) control.setAttribute("aria-describedby", [...ids].join(" "));
  else control.removeAttribute("aria-describedby");
}

export function clearErrors() {
  for (const element of document.querySelectorAll(".field-error[data-for]")) {
    const control = $(element.dataset.for);
    if (control) {
      control.removeAttribute("aria-invalid");
      describedBy(control, element.id, false);
    }
    element.remove();
  }
  for (const element of document.querySelectorAll(".invalid")) element.classList.remove("invalid");
  $("problem").hidden = true;
  $("problem").replaceChildren();
}

/** Show `text` next to `control` (an input, select or table header). */
function attachError(control, text) {
  const id = `${control.id}-error`;
  let element = $(id);
  if (!element) {
    element = document.createElement("p");
    element.className = "field-error";
    element.id = id;
    element.dataset.for = control.id;
    if (control.tagName === "TH") control.append(element);
    else control.insertAdjacentElement("afterend", element);
  }
  element.textContent = element.textContent ? `${element.textContent}; ${text}` : text;
  control.classList.add("invalid");
  if (control.tagName !== "TH") {
    control.setAttribute("aria-invalid", "true");
    describedBy(control, id, true);
  }
}

/** The controls that produced the value at `path` ("wing.chord[3]", "flight.velocity"). */
function controlsFor(path) {
  const exact = document.querySelector(`[data-path="${CSS.escape(path)}"]`);
  for (const resolve of resolvers) {
    const found = resolve(path, exact);
    if (found) return found.filter(Boolean);
  }
  return exact ? [exact] : [];
}

function stationWords(path) {
  const match = /^wing\.(\w+)\[(\d+)\]/.exec(path);
  return match ? `station ${match[2]} (${match[1]}): ` : "";
}

function showFieldErrors(errors) {
  let first = null;
  for (const { field, reason } of errors) {
    for (const control of controlsFor(field)) {
      const inTable = control.closest("table") !== null;
      attachError(control, inTable ? reason : `${stationWords(field)}${reason}`);
      const details = control.closest("details");
      if (details) details.open = true;
      first ??= control.tagName === "TH" ? null : control;
    }
  }
  return first;
}

function plainProblem(error, velocity) {
  const p = error.problem;
  const type = p.type ?? "";
  if (type.endsWith("/no-equilibrium")) {
    const v = p.velocity ?? velocity;
    const fold = p.fold_velocity;
    // Trimmed flight (a weight to carry) has its own reasons, which the solver words best: the lift
    // needs more than the largest angle of attack, or the trimmed branch turns back.
    if (/trim|alpha =|any angle of attack/i.test(p.detail ?? "")) {
      return { title: `No equilibrium at ${v} m/s`, text: p.detail };
    }
    return {
      title: `No equilibrium at ${v} m/s`,
      text:
        fold != null
          ? `This wing twists until it diverges: its equilibria end at the fold speed, ${fold.toFixed(2)} m/s, and none exists faster. Fly slower than ${fold.toFixed(2)} m/s, or make the wing stiffer in torsion (GJ) or move its elastic axis forward.`
          : "This wing twists until it diverges at this airspeed, and the fold speed where its equilibria end could not be located. Try a lower airspeed.",
    };
  }
  if (type.endsWith("/key-missing") || type.endsWith("/key-invalid")) {
    askForKey();
    const missing = type.endsWith("/key-missing");
    return {
      title: missing ? "This service needs an API key" : "The API key was not accepted",
      text: `${missing ? "Enter" : "Check"} the key its operator gave you under "API key" at the top of the page.`,
    };
  }
  if (type.endsWith("/invalid-input")) {
    const n = p.error_count ?? p.errors?.length ?? 0;
    return { title: "Check the highlighted inputs", text: `The service found ${n} invalid input${n === 1 ? "" : "s"}; each reason is shown next to its field.` };
  }
  if (type.endsWith("/not-converged")) {
    return { title: "The solver did not converge", text: `${p.detail} Try a lower airspeed.` };
  }
  if (error.status === 503) {
    return { title: p.title ?? "The service is busy", text: `${p.detail ?? ""} Try again in ${p.retryAfter ?? "a few"} s.` };
  }
  return { title: p.title ?? `HTTP ${error.status}`, text: p.detail ?? "" };
}

/** Show `error` (an api.ProblemError) in the problem box, its field errors next to their inputs;
 * `velocity`: the run's airspeed, for a problem that does not say it. */
export function showProblem(error, velocity) {
  const box = $("problem");
  box.replaceChildren();
  box.dataset.type = error.problem.type ?? "";
  const { title, text } = plainProblem(error, velocity);
  const heading = document.createElement("strong");
  heading.textContent = title;
  const body = document.createElement("p");
  body.textContent = text;
  box.append(heading, body);
  let first = null;
  if (error.problem.errors?.length) {
    first = showFieldErrors(error.problem.errors);
    const list = document.createElement("ul");
    for (const { field, reason } of error.problem.errors) {
      const item = document.createElement("li");
      const code = document.createElement("code");
      code.textContent = field;
      item.append(code, `: ${reason}`);
      list.append(item);
    }
    box.append(list);
  }
  box.hidden = false;
  if (first) {
    first.focus({ preventScroll: true }); // keyboard users land on the first input to fix
    first.scrollIntoView({ block: "center" });
  } else {
    box.scrollIntoView({ block: "nearest" });
  }
}
