// The page: wing editor, flight panel, Solve and Sweep, results and figures. Plain ES modules,
// no build step; every asset comes from this app (see app/routes/page.py).

import * as api from "./api.js";
import { downloadBlob, downloadJSON, downloadText, toCSV } from "./download.js";
import {
  CHORDWISE_FIELD,
  CONCENTRATED_MASS_COLUMNS,
  FLIGHT_FIELDS,
  FLUTTER_FIELDS,
  MASS_FIELDS,
  OPTIONAL_FIELDS,
  PLANFORM_FIELDS,
  SPAR_FIELDS,
  STIFFNESS_LAW_KEYS,
  SWEEP_FIELDS,
  applyLimits,
  controlValue,
  panelsForHinge,
  renderField,
  setPath,
} from "./fields.js";
import * as figures from "./figures.js";
import { askForKey, installKeyBox } from "./key.js";
import { RowTable } from "./rows.js";
import { ControlSurfaceTable } from "./surfaces.js";
import { StationTable, stationsFromPlanform } from "./wing.js";

const $ = (id) => document.getElementById(id);

const state = {
  mode: "planform",
  flightMode: "alpha", // "alpha" or "weight" (trimmed)
  stiffness: "laws", // "laws" (EI, GJ from the table) or "spar"
  controls: {}, // key -> {field, control}
  extra: [], // optional fields this API version has: {field, control}
  passThrough: {}, // wing keys loaded from JSON that the editor does not know
  options: {}, // solver options loaded from JSON (sent as given; the page sets only safety_factor)
  solve: null, // {request, response, rigid, rigidNote}
  sweep: null, // {request, response}
  controlRun: null, // {request, response} of POST /controls
  flutter: null, // {request, response} of POST /flutter
  mass: false, // whether the wing carries its mass model (wing.mass, for flutter)
  runs: { solve: 0, sweep: 0, controls: 0, flutter: 0, failed: 0 },
  busy: false,
  abort: null,
};

// What tests (and curious users) can read: window.__flexwing.figures["14.2"].series, etc.
window.__flexwing = {
  figures: figures.registry,
  state,
  ready: false,
  get totals() {
    return state.solve?.response.totals ?? null;
  },
};

// ------------------------------------------------------------------------------------ editor

const table = new StationTable($("stations-table"), {
  onEdit: () => {
    if (state.mode !== "table") setMode("table");
    updateCount();
  },
});

const surfaces = new ControlSurfaceTable($("surfaces-table"), { onChange: () => updateSurfaces() });

/** The surfaces' count, whether the controls sweep is offered, and the chordwise panels they need. */
function updateSurfaces({ raise = false } = {}) {
  const n = surfaces.rows;
  $("surface-count").textContent = n ? String(n) : "none";
  $("controls-actions").hidden = n === 0;
  $("chordwise").hidden = n === 0;
  const hinges = surfaces.read().map((s) => s.hinge).filter((h) => h != null && h > 0 && h < 1);
  const need = hinges.length ? Math.max(...hinges.map(panelsForHinge)) : 1;
  const control = state.controls.chordwise_panels?.control;
  if (!control) return;
  let raised = false;
  if (raise && (value("chordwise_panels") ?? 0) < need) {
    control.value = String(Math.max(need, 3));
    raised = true;
  }
  $("chordwise-note").textContent = n
    ? `Control surfaces need chordwise panels: a hinge at ${Math.max(...hinges, 0)} of the chord needs at least ${need} (a whole panel aft of it)` +
      (raised ? `; set to ${control.value}.` : ".") +
      " Every run of this wing (solve, sweep, controls, flutter) uses them."
    : "";
}

const concentrated = new RowTable($("concentrated-table"), {
  columns: CONCENTRATED_MASS_COLUMNS,
  path: "wing.mass.concentrated",
  id: "concentrated",
  onChange: () => updateConcentrated(),
});

function updateConcentrated() {
  $("concentrated-count").textContent = concentrated.rows ? String(concentrated.rows) : "none";
}

function setMass(on) {
  state.mass = on;
  $("mass-on").checked = on;
  $("mass").hidden = !on;
  $("concentrated-details").hidden = !on;
  $("flutter-hint").textContent = on
    ? "Enter in a flutter field runs it."
    : 'Needs the wing\'s mass: tick "the wing has a mass model" under Wing.';
}

function render(fields, parent, options = {}) {
  for (const field of fields) {
    const control = renderField(field, parent, options);
    state.controls[field.key] = { field, control };
  }
}

function value(key) {
  const { field, control } = state.controls[key];
  return controlValue(control, field.kind);
}

function planformValues() {
  return Object.fromEntries(PLANFORM_FIELDS.map((f) => [f.key, value(f.key)]));
}

function regenerate() {
  table.fill(stationsFromPlanform(planformValues()));
  updateCount();
}

function updateCount() {
  $("station-count").textContent = String(table.rows);
}

function setMode(mode) {
  state.mode = mode;
  $(`mode-${mode}`).checked = true;
  $("planform").disabled = mode === "table";
  $("planform-note").textContent =
    mode === "planform"
      ? "The station table follows these numbers."
      : 'The station table was edited or loaded, so the planform numbers no longer apply; choose "planform numbers" to fill the table from them again.';
  if (mode === "planform") regenerate();
}

function wing() {
  const result = { ...state.passThrough, ...table.read() };
  if (state.stiffness === "spar") {
    // Stiffness or spar, not both: the tube gives EI and GJ.
    delete result.bending_stiffness;
    delete result.torsional_stiffness;
    const spar = {};
    for (const field of SPAR_FIELDS) {
      if (field.path.startsWith("wing.")) setPath(spar, field.path, value(field.key));
    }
    result.spar = spar.wing.spar;
  } else if (result.spar) {
    // A spar loaded from JSON that the spar's fields cannot hold: sent as given, without EI, GJ.
    delete result.bending_stiffness;
    delete result.torsional_stiffness;
  }
  if (surfaces.rows) result.control_surfaces = surfaces.read();
  if (state.mass) {
    const mass = {};
    for (const field of MASS_FIELDS) setPath(mass, field.path, value(field.key));
    result.mass = mass.wing.mass;
    if (concentrated.rows) result.mass.concentrated = concentrated.read();
  }
  for (const { field, control } of state.extra) {
    if (field.path?.startsWith("wing.") && field.kind !== "column") {
      const v = controlValue(control, field.kind);
      if (v !== null && v !== "") setPath(result, field.path.slice("wing.".length), v);
    }
  }
  return result;
}

function flight({ withVelocity }) {
  const result = {};
  for (const field of FLIGHT_FIELDS) {
    if (field.solveOnly && !withVelocity) continue;
    if (field.flightMode && field.flightMode !== state.flightMode) continue;
    setPath(result, field.path, value(field.key));
  }
  for (const { field, control } of state.extra) {
    if (field.path?.startsWith("flight.")) {
      const v = controlValue(control, field.kind);
      if (v !== null && v !== "") setPath(result, field.path, v);
    }
  }
  return result.flight;
}

/** Solver options: those loaded from JSON, as given, and the one the page sets (the safety
 * factor of a spar's failure margin). */
function withOptions(request) {
  if (Object.keys(state.options).length) request.options = { ...state.options };
  if (state.stiffness === "spar") setPath(request, "options.safety_factor", value("safety_factor"));
  if (request.wing.control_surfaces?.length) setPath(request, CHORDWISE_FIELD.path, value(CHORDWISE_FIELD.key));
  return request;
}

function solveRequest() {
  return withOptions({ wing: wing(), flight: flight({ withVelocity: true }) });
}

function sweepRequest(fields = SWEEP_FIELDS) {
  const request = withOptions({ wing: wing(), flight: flight({ withVelocity: false }) });
  for (const field of fields) setPath(request, field.path, value(field.key));
  return request;
}

/** POST /controls: the sweep's airspeeds, the wing's control surfaces. */
const controlsRequest = () => sweepRequest(SWEEP_FIELDS);

/** POST /flutter: the flutter panel's airspeeds, the wing with its mass. */
const flutterRequest = () => sweepRequest(FLUTTER_FIELDS);

/** The flight panel's choice: fly at an angle of attack, or trimmed to carry a weight. */
function setFlightMode(mode) {
  state.flightMode = mode;
  $(`flight-mode-${mode}`).checked = true;
  for (const wrap of $("flight").querySelectorAll(".field[data-flight-mode]")) {
    wrap.hidden = wrap.dataset.flightMode !== mode;
  }
  $("sweep-same").textContent = mode === "weight" ? "weight, load factor" : "angle of attack";
  $("flutter-same").textContent = $("sweep-same").textContent;
}

/** Where EI and GJ come from: the laws (or the table's columns), or a tube spar. */
function setStiffness(source) {
  state.stiffness = source;
  $(`stiffness-${source}`).checked = true;
  const spar = source === "spar";
  $("spar").hidden = !spar;
  for (const key of STIFFNESS_LAW_KEYS) state.controls[key].control.closest(".field").hidden = spar;
  $("stiffness-note").textContent = spar
    ? "EI and GJ follow from the tube (the station table's EI and GJ columns are not sent); the results add its stresses, failure margin and mass."
    : "";
}

/** Optional fields: shown when the running server's OpenAPI document has them. */
async function addOptionalFields() {
  const doc = await api.openapi();
  const schemas = doc?.components?.schemas ?? {};
  // Trim and the tube spar came with later API versions: offered when this one has them.
  $("flight-mode").hidden = !schemas.FlightAtWeight;
  $("stiffness-from").hidden = !schemas.TubeSpar;
  // Control surfaces (with the controls sweep) and the mass model (with flutter), likewise.
  const surfaceSchema = schemas.Wing?.properties?.control_surfaces && schemas.ControlSurface;
  $("surfaces-details").hidden = !surfaceSchema;
  if (surfaceSchema) surfaces.setSchema(surfaceSchema);
  applyLimits(state.controls.chordwise_panels.control, schemas.SolverOptions?.properties?.chordwise_panels);
  const massSchema = schemas.Wing?.properties?.mass && schemas.MassModel;
  const flutter = Boolean(massSchema && schemas.FlutterRequest);
  for (const id of ["mass-from", "flutter", "flutter-actions"]) $(id).hidden = !flutter;
  for (const field of MASS_FIELDS) {
    const property = massSchema?.properties?.[field.path.split(".").at(-1)];
    const { control } = state.controls[field.key];
    applyLimits(control, property);
    if (property?.description) control.title = property.description;
  }
  if (schemas.ConcentratedMass) concentrated.setSchema(schemas.ConcentratedMass);
  const stations = table.read(); // before a column is added: read() reads every column's cells
  let columns = false;
  for (const field of OPTIONAL_FIELDS) {
    const property = schemas[field.schema]?.properties?.[field.property];
    if (!property) continue;
    const described = { ...field, hint: property.description };
    if (field.kind === "column") {
      table.addColumn({ key: field.property, label: field.label, unit: field.unit, value: field.value });
      columns = true;
      continue;
    }
    const parent = field.schema === "Flight" ? $("flight") : $("wing-extra");
    state.extra.push({ field: described, control: renderField(described, parent) });
  }
  if (columns) table.fill(stations);
}

// ------------------------------------------------------------------------------------ errors

function describedBy(control, id, add) {
  const ids = new Set((control.getAttribute("aria-describedby") ?? "").split(" ").filter(Boolean));
  if (add) ids.add(id);
  else ids.delete(id);
  if (ids.size) control.setAttribute("aria-describedby", [...ids].join(" "));
  else control.removeAttribute("aria-describedby");
}

function clearErrors() {
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
  const found = [];
  const exact = document.querySelector(`[data-path="${CSS.escape(path)}"]`);
  const match = /^wing\.(\w+)(?:\[(\d+)\])?/.exec(path);
  if (match) {
    const [, list, index] = match;
    // In planform mode the numbers that generated the value come first (focus goes there).
    if (state.mode === "planform") {
      for (const field of PLANFORM_FIELDS.filter((f) => f.feeds?.includes(list))) {
        const last = table.rows - 1;
        if (field.key === "root_chord" && index !== undefined && Number(index) === last && last > 0) continue;
        if (field.key === "tip_chord" && index !== undefined && Number(index) === 0) continue;
        found.push(state.controls[field.key].control);
      }
    }
    if (exact) found.push(exact);
    else {
      const cell = index !== undefined ? $(`cell-${list}-${index}`) : null;
      found.push(cell ?? $(`col-${list}`));
    }
  } else if (exact) {
    found.push(exact);
  }
  return found.filter(Boolean);
}

function stationWords(path) {
  const match = /^wing\.(\w+)\[(\d+)\]/.exec(path);
  return match ? `station ${match[2]} (${match[1]}): ` : "";
}

function showFieldErrors(errors) {
  let first = null;
  const unplaced = [];
  for (const { field, reason } of errors) {
    const controls = controlsFor(field);
    if (!controls.length) unplaced.push({ field, reason });
    for (const control of controls) {
      const inTable = control.closest("#stations-table, #surfaces-table, #concentrated-table") !== null;
      attachError(control, inTable ? reason : `${stationWords(field)}${reason}`);
      const details = control.closest("details");
      if (details) details.open = true;
      first ??= control.tagName === "TH" ? null : control;
    }
  }
  return { first, unplaced };
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

function showProblem(error, velocity) {
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
    const placed = showFieldErrors(error.problem.errors);
    first = placed.first;
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

// -------------------------------------------------------------------------------- busy state

let ticker = null;
const RUN_BUTTONS = ["solve-button", "sweep-button", "controls-button", "flutter-button"];

function setBusy(message, { cancellable = false } = {}) {
  state.busy = true;
  const started = performance.now();
  $("progress").hidden = false;
  $("progress").removeAttribute("value");
  $("status-text").textContent = message;
  $("cancel").hidden = !cancellable;
  $("results").setAttribute("aria-busy", "true");
  for (const id of RUN_BUTTONS) $(id).disabled = true;
  clearInterval(ticker);
  ticker = setInterval(() => {
    $("status-text").dataset.elapsed = `${((performance.now() - started) / 1000).toFixed(1)} s`;
  }, 100);
}

function setProgress({ done, total, message }) {
  if (total > 0 && done > 0) {
    $("progress").max = total;
    $("progress").value = done;
  }
  if (message) $("status-text").textContent = message;
}

function setIdle(message) {
  state.busy = false;
  clearInterval(ticker);
  $("progress").hidden = true;
  $("status-text").textContent = message;
  delete $("status-text").dataset.elapsed;
  $("cancel").hidden = true;
  $("results").removeAttribute("aria-busy");
  for (const id of RUN_BUTTONS) $(id).disabled = false;
}

// ------------------------------------------------------------------------------------- solve

async function runSolve() {
  if (state.busy) return;
  clearErrors();
  const request = solveRequest();
  setBusy(`Solving at ${request.flight.velocity} m/s`);
  let response;
  try {
    response = await api.solve(request);
  } catch (error) {
    state.runs.failed++;
    setIdle("Solve failed.");
    if (error instanceof api.ProblemError) showProblem(error, request.flight.velocity);
    else throw error;
    return;
  }
  const rigid = { panels: { y: response.panels.y, lift_per_span: response.panels.rigid_lift_per_span } };
  const rigidNote =
    "Rigid: the jig shape's own lattice solution at the same condition (panels.rigid_lift_per_span), " +
    `${f(response.totals.rigid_lift, 1)} N in all.`;
  state.solve = { request, response, rigid, rigidNote };
  state.runs.solve++;
  renderSolve();
  setIdle(`Solved at ${request.flight.velocity} m/s in ${(response.solver.seconds * 1000).toFixed(1)} ms of solver time.`);
}

const f = (x, digits) => (x == null ? "n/a" : x.toFixed(digits));
const signed = (x, digits) => (x == null ? "n/a" : `${x >= 0 ? "+" : ""}${x.toFixed(digits)}`);

const trimmed = (r) => r.totals.lift_effectiveness != null;
const withSpar = (r) => r.totals.failure_margin != null || r.totals.spar_mass != null;
const MPa = (x) => (x == null ? "n/a" : `${(x / 1e6).toFixed(1)} MPa`);

// [key, label, format, when]: a card is shown when `when` (if any) holds for the response.
const TOTALS = [
  ["alpha", "Angle of attack (trimmed)", (r) => `${f(r.totals.alpha, 2)} deg`, trimmed],
  ["lift", "Lift", (r) => `${f(r.totals.lift, 1)} N`],
  ["rigid_alpha", "Rigid jig's alpha for this lift", (r) => `${f(r.totals.rigid_alpha, 2)} deg`, trimmed],
  ["lift_effectiveness", "Lift effectiveness (flexible / rigid lift slope)", (r) => f(r.totals.lift_effectiveness, 3), trimmed],
  ["rigid_lift", "Rigid lift (jig shape)", (r) => `${f(r.totals.rigid_lift, 1)} N`, (r) => !trimmed(r)],
  ["lift_amplification", "Lift amplification L / L_rigid", (r) => f(r.totals.lift_amplification, 3), (r) => !trimmed(r)],
  ["tip_twist", "Tip twist (nose-up > 0)", (r) => `${signed(r.totals.tip_twist, 2)} deg`],
  ["tip_heave", "Tip heave", (r, w) => `${f(r.totals.tip_heave, 4)} m (${f((100 * r.totals.tip_heave) / w.y.at(-1), 1)} % of b/2)`],
  ["root_bending_moment", "Root bending moment", (r) => `${f(r.totals.root_bending_moment, 1)} N·m`],
  ["root_torque", "Root torque", (r) => `${f(r.totals.root_torque, 2)} N·m`],
  ["margin", "Stability margin q / q_div (local)", (r) => `${f(r.stability.margin, 3)} (${r.stability.stable ? "stable" : "UNSTABLE"})`],
  ["divergence_velocity", "Linear divergence speed", (r) => `${f(r.stability.divergence_velocity, 2)} m/s`],
  ["CL", "CL (jig area)", (r) => f(r.totals.CL, 3)],
  ["induced_drag", "Induced drag", (r) => `${f(r.totals.induced_drag, 2)} N`],
  [
    "failure_margin",
    "Spar failure margin (yield / (SF × von Mises) - 1)",
    (r) => `${signed(r.totals.failure_margin, 2)} (${r.totals.failure_margin >= 0 ? "holds" : "YIELDS"})`,
    withSpar,
  ],
  ["max_von_mises_stress", "Largest von Mises stress", (r) => `${MPa(r.totals.max_von_mises_stress)} at y = ${f(r.totals.max_von_mises_y, 2)} m`, withSpar],
  ["spar_mass", "Spar mass (both halves)", (r) => `${f(r.totals.spar_mass, 2)} kg`, withSpar],
  ["solver", "Solver", (r) => `${r.solver.iterations} Newton iterations${r.solver.cached ? ", from the cache" : ""}`],
];

function renderSolve() {
  const { request, response, rigid, rigidNote } = state.solve;
  $("totals").replaceChildren(
    ...TOTALS.filter(([, , , when]) => !when || when(response)).map(([key, label, format]) => {
      const item = document.createElement("div");
      item.dataset.total = key;
      const term = document.createElement("dt");
      term.textContent = label;
      const value = document.createElement("dd");
      value.textContent = format(response, request.wing);
      item.append(term, value);
      return item;
    }),
  );
  const { velocity, alpha, weight, load_factor: n, density } = request.flight;
  $("totals-condition").textContent =
    weight !== undefined
      ? `${velocity} m/s, weight ${weight} N${n !== undefined && n !== 1 ? ` × n ${n}` : ""} (trimmed: alpha ${f(response.totals.alpha, 2)} deg), ${density} kg/m^3`
      : `${velocity} m/s, alpha ${alpha} deg, ${density} kg/m^3`;
  $("rigid-note").textContent = rigidNote;
  figures.drawSpanwise(response, rigid);
  figures.drawLoads(response);
  renderStress(request, response);
  renderValidity(response);
  updateShapeChoices("solve");
  for (const id of ["download-json", "download-stations", "download-panels"]) $(id).disabled = false;
}

/** The spar's stresses under figure 14.3, when the answer has them; else the figure is hidden. */
function renderStress(request, response) {
  const spar = request.wing.spar;
  if (!response.stations.von_mises_stress || !spar) {
    figures.clear("stress");
    $("fig-stress").hidden = true;
    return;
  }
  $("fig-stress").hidden = false;
  const safety = request.options?.safety_factor ?? 1;
  figures.drawStress(response, spar.material.yield_stress, safety);
  const t = response.totals;
  $("stress-note").textContent =
    `Tube D ${spar.outer_diameter} m, wall ${spar.wall_thickness} m: ${f(t.spar_mass, 2)} kg for both halves; ` +
    `root bending stress ${MPa(t.root_bending_stress)}` +
    (t.rigid_root_bending_stress != null ? ` (rigid jig: ${MPa(t.rigid_root_bending_stress)})` : "") +
    `; failure margin ${signed(t.failure_margin, 2)} at safety factor ${safety}.`;
}

// ---------------------------------------------------------------------------------- validity

// Findings about the spanwise figure's quantities are listed under it (their stations marked on
// its charts); the others (near divergence) next to the totals, beside the stability margin.
const SPANWISE_FINDINGS = new Set(["large_deflection", "large_twist", "section_stall"]);
const SHORT_FINDINGS = { large_deflection: "deflection", large_twist: "twist", section_stall: "stall", near_divergence: "near divergence" };

const titleOf = (code) => figures.FINDING_TITLES[code] ?? code.replaceAll("_", " ");
const codesOf = (findings) => [...new Set(findings.map((f) => f.code))];

function findingItem(finding) {
  const item = document.createElement("li");
  item.dataset.code = finding.code;
  if (finding.measure) item.dataset.measure = finding.measure;
  const title = document.createElement("strong");
  title.textContent = `${titleOf(finding.code)}.`;
  item.append(title, finding.message);
  return item;
}

function renderValidity(response) {
  const findings = response.validity ?? [];
  const spanwise = findings.filter((f) => SPANWISE_FINDINGS.has(f.code));
  $("findings-14-2").replaceChildren(...spanwise.map(findingItem));
  $("findings-totals").replaceChildren(...findings.filter((f) => !SPANWISE_FINDINGS.has(f.code)).map(findingItem));
  $("validity").dataset.state = findings.length ? "findings" : "clear";
  $("validity-summary").textContent = findings.length
    ? `Beyond the model's validity: ${codesOf(findings).map(titleOf).join(", ").toLowerCase()}` +
      (spanwise.length ? " (stations marked in Figure 14.2, details under it)." : ".")
    : "Within the model's validity: deflection, twist, section lift coefficients and stability margin are all within their limits.";
}

function renderOnsets(response) {
  $("findings-14-4").replaceChildren(
    ...(response.validity ?? []).map((onset) => {
      const item = document.createElement("li");
      item.dataset.code = onset.code;
      item.dataset.velocity = String(onset.velocity);
      item.textContent = onset.message;
      return item;
    }),
  );
}

// ------------------------------------------------------------------------------------- sweep

async function runSweep() {
  if (state.busy) return;
  clearErrors();
  const request = sweepRequest();
  const controller = new AbortController();
  state.abort = controller;
  setBusy("Sweeping", { cancellable: true });
  try {
    const response = await api.runSweep(request, { signal: controller.signal, onProgress: setProgress });
    state.sweep = { request, response };
    state.runs.sweep++;
    renderSweep();
    const solved = response.points.filter((p) => p.status === "equilibrium").length;
    setIdle(`Swept ${response.points.length} airspeeds: ${solved} equilibria.`);
  } catch (error) {
    state.runs.failed++;
    if (error.name === "AbortError") {
      setIdle("Sweep cancelled.");
    } else if (error instanceof api.ProblemError) {
      setIdle("Sweep failed.");
      showProblem(error);
    } else {
      setIdle("Sweep failed.");
      throw error;
    }
  } finally {
    state.abort = null;
  }
}

const SWEEP_COLUMNS = [
  ["V [m/s]", (p) => f(p.velocity, 2)],
  ["status", (p) => p.status.replace("_", " ")],
  ["lift [N]", (p) => f(p.equilibrium?.totals.lift, 1)],
  ["L / L_rigid", (p) => f(p.equilibrium?.totals.lift_amplification, 3), "alpha"],
  ["alpha [deg]", (p) => f(p.equilibrium?.totals.alpha, 2), "weight"],
  ["lift effectiveness", (p) => f(p.equilibrium?.totals.lift_effectiveness, 3), "weight"],
  ["tip twist [deg]", (p) => signed(p.equilibrium?.totals.tip_twist, 2)],
  ["tip heave [m]", (p) => f(p.equilibrium?.totals.tip_heave, 3)],
  ["margin", (p) => f(p.equilibrium?.stability.margin, 3)],
  ["beyond the model", (p) => (p.equilibrium ? codesOf(p.equilibrium.validity ?? []).map((c) => SHORT_FINDINGS[c] ?? c).join(", ") || "-" : "")],
];

function renderSweep() {
  const { request, response } = state.sweep;
  const { fit, linear, fold } = response.divergence;
  const mode = request.flight.weight !== undefined ? "weight" : "alpha";
  const columns = SWEEP_COLUMNS.filter(([, , only]) => !only || only === mode);
  figures.drawSweep(response, request.flight.density);
  const notes = [];
  if (fit.velocity != null) {
    notes.push(
      `Dashed: the study's fit 1/A = ${f(fit.intercept, 3)} ${fit.slope < 0 ? "-" : "+"} ${Math.abs(fit.slope).toExponential(3)} q over ${fit.points_used} stable points ` +
        `(A = ${figures.AMPLIFICATION_WORDS[fit.amplification] ?? fit.amplification}), drawn to 92 % of its V_div ${f(fit.velocity, 2)} m/s.`,
    );
  } else notes.push(`No fit: ${fit.reason}.`);
  if (fold.kind === "trimmed_stability_limit") {
    notes.push(
      fold.velocity != null
        ? `Trimmed divergence: at ${f(fold.lift, 1)} N the trimmed wing loses static stability at ${f(fold.velocity, 2)} m/s (shaded beyond: equilibria exist there but are unstable).`
        : `Trimmed stability limit: ${fold.reason}.`,
    );
  } else {
    notes.push(fold.velocity != null ? `Equilibria end at the fold, ${f(fold.velocity, 2)} m/s (shaded beyond).` : `Fold: ${fold.reason}.`);
  }
  notes.push(linear.velocity != null ? `Linear divergence at the jig: ${f(linear.velocity, 2)} m/s.` : `Linear divergence: ${linear.reason}.`);
  $("sweep-note").textContent = notes.join(" ");
  const head = $("sweep-table").tHead;
  head.replaceChildren();
  const headRow = head.insertRow();
  for (const [label] of columns) {
    const th = document.createElement("th");
    th.scope = "col";
    th.textContent = label;
    headRow.append(th);
  }
  const body = $("sweep-table").tBodies[0];
  body.replaceChildren();
  for (const point of response.points) {
    const row = body.insertRow();
    row.dataset.status = point.status;
    for (const [, format] of columns) row.insertCell().textContent = format(point);
    if (point.no_equilibrium) row.title = point.no_equilibrium.reason;
    const findings = point.equilibrium?.validity ?? [];
    if (findings.length) {
      row.cells[row.cells.length - 1].classList.add("beyond");
      row.cells[row.cells.length - 1].title = findings.map((x) => x.message).join("\n");
    }
  }
  renderOnsets(response);
  const fastest = response.points.findLastIndex((p) => p.status === "equilibrium");
  updateShapeChoices(fastest >= 0 ? `sweep-${fastest}` : undefined);
  $("download-sweep").disabled = false;
  $("download-json").disabled = false;
}

// ------------------------------------------------------------------ controls and flutter runs

/** Run one airspeed job (`kind`: "controls" or "flutter") of `request` through `call`, as the
 * sweep runs: busy with Cancel and progress, its 422 next to the fields; resolves with the answer
 * (null when it failed or was cancelled). */
async function runAirspeedJob(kind, request, call, words) {
  if (state.busy) return null;
  clearErrors();
  const controller = new AbortController();
  state.abort = controller;
  setBusy(words, { cancellable: true });
  try {
    const response = await call(request, { signal: controller.signal, onProgress: setProgress });
    state.runs[kind]++;
    return response;
  } catch (error) {
    state.runs.failed++;
    if (error.name === "AbortError") {
      setIdle(`${words}: cancelled.`);
    } else if (error instanceof api.ProblemError) {
      setIdle(`${words}: failed.`);
      showProblem(error);
    } else {
      setIdle(`${words}: failed.`);
      throw error;
    }
    return null;
  } finally {
    state.abort = null;
  }
}

async function runControls() {
  if (!surfaces.rows) return;
  const request = controlsRequest();
  const response = await runAirspeedJob("controls", request, api.runControls, "Control effectiveness");
  if (!response) return;
  state.controlRun = { request, response };
  renderControls();
  $("download-json").disabled = false;
  $("download-controls").disabled = false;
  setIdle(`Control effectiveness of ${response.reversals.length} surface${response.reversals.length === 1 ? "" : "s"} at ${response.points.length} airspeeds.`);
}

/** Which comes first for one surface, in words. */
function firstWords(summary, symmetric, antisymmetric) {
  const reversal = summary.reversal.velocity;
  const problem = summary.kind === "aileron" ? "antisymmetric" : "symmetric";
  const divergence = summary.kind === "aileron" ? antisymmetric : symmetric;
  const divergenceText = divergence != null ? `${problem} divergence at ${f(divergence, 2)} m/s` : `no ${problem} divergence`;
  const name = `The ${summary.kind} "${summary.name}"`;
  if (summary.first === "reversal") {
    return `${name}: reversal comes first, at ${f(reversal, 2)} m/s, before ${divergenceText}.`;
  }
  if (summary.first === "divergence") {
    return `${name}: divergence comes first (${divergenceText}), before ${reversal != null ? `its reversal at ${f(reversal, 2)} m/s` : "any reversal"}.`;
  }
  return `${name}: neither reverses nor diverges (${summary.reversal.reason ?? divergenceText}).`;
}

function renderControls() {
  const { request, response } = state.controlRun;
  $("fig-controls").hidden = false;
  figures.drawControls(response);
  const symmetric = response.symmetric_divergence.velocity;
  const antisymmetric = response.antisymmetric_divergence.velocity;
  $("controls-first").textContent = response.reversals.map((r) => firstWords(r, symmetric, antisymmetric)).join(" ");
  const crossings = response.reversals
    .filter((r) => r.crossing?.velocity != null)
    .map((r) => `${r.name}'s effectiveness changes sign between the sweep's airspeeds at ${f(r.crossing.velocity, 2)} m/s`);
  $("controls-note").textContent =
    `Reversal: the linear reversal of the unloaded jig (dashed, one per surface); divergence: the jig's symmetric ` +
    `(${f(symmetric, 2)} m/s) and antisymmetric (${f(antisymmetric, 2)} m/s) divergence, the latter the problem an aileron acts in. ` +
    `${request.options?.chordwise_panels ?? 1} chordwise panels per strip.` +
    (crossings.length ? ` ${crossings.join("; ")}.` : "");
  $("fig-controls").scrollIntoView({ block: "nearest" });
}

async function runFlutter() {
  if (!state.mass) {
    clearErrors();
    showProblem(new api.ProblemError(0, { title: "Flutter needs the wing's mass", detail: 'Tick "the wing has a mass model" under Wing and give its mass per length, centre of gravity and inertia.' }));
    $("mass-on").focus();
    return;
  }
  const request = flutterRequest();
  const response = await runAirspeedJob("flutter", request, api.runFlutter, "Flutter");
  if (!response) return;
  state.flutter = { request, response };
  renderFlutter();
  $("download-json").disabled = false;
  $("download-flutter").disabled = false;
  setIdle(`Flutter: ${response.points.length} airspeeds, ${response.modes.length} modes.`);
}

function flutterWords(response) {
  const { flutter: onset, no_flutter: none, divergence } = response;
  const words = [];
  if (response.status === "flutter") {
    words.push(
      `Flutter at ${f(onset.velocity, 2)} m/s: mode ${onset.mode + 1}'s damping crosses zero there, at ${f(onset.frequency, 1)} rad/s ` +
        `(${f(onset.frequency / (2 * Math.PI), 2)} Hz, reduced frequency ${f(onset.reduced_frequency, 3)}).`,
    );
  } else if (response.status === "no_flutter_in_range") {
    words.push(
      `No flutter between ${f(none.searched_from, 2)} and ${f(none.searched_to, 2)} m/s: every mode stays damped; the least damping, ` +
        `${none.least_damping.toPrecision(3)}, is mode ${none.least_damped_mode + 1}'s at ${f(none.least_damped_velocity, 2)} m/s.`,
    );
  } else {
    words.push("No airspeed has a static equilibrium to linearise about: no flutter analysis was possible (each point says why).");
  }
  if (divergence) {
    words.push(`Divergence (${divergence.kind.replaceAll("_", " ")}) at ${f(divergence.velocity, 2)} m/s${divergence.within_range ? "" : ", beyond the airspeeds analysed"}.`);
    if (onset) words.push(onset.velocity < divergence.velocity ? "Flutter comes first." : "Divergence comes first.");
  } else {
    words.push("No divergence.");
  }
  return words.join(" ");
}

function renderFlutter() {
  const { response } = state.flutter;
  $("fig-flutter").hidden = false;
  figures.drawFlutter(response);
  $("flutter-status").textContent = flutterWords(response);
  $("fig-flutter").dataset.status = response.status;
  const lost = response.points.filter((p) => p.status !== "solved").map((p) => f(p.velocity, 2));
  $("flutter-note").textContent =
    `Linearised about ${response.about === "jig" ? "the unloaded jig" : "the static equilibrium at each airspeed"}; ${response.aerodynamics} aerodynamics, ` +
    `${response.unsteady === "theodorsen" ? "Theodorsen's lag" : "quasi-steady"}.` +
    (lost.length ? ` No equilibrium (no roots) at ${lost.join(", ")} m/s.` : "");
  $("fig-flutter").scrollIntoView({ block: "nearest" });
}

// ------------------------------------------------------------------------------ figure 14.5

function shapeChoices() {
  const choices = [];
  if (state.solve) {
    choices.push({ value: "solve", label: `Solve: ${state.solve.request.flight.velocity} m/s`, wing: state.solve.request.wing, equilibrium: state.solve.response, velocity: state.solve.request.flight.velocity });
  }
  if (state.sweep) {
    state.sweep.response.points.forEach((point, i) => {
      if (point.status === "equilibrium") {
        choices.push({ value: `sweep-${i}`, label: `Sweep: ${f(point.velocity, 2)} m/s`, wing: state.sweep.request.wing, equilibrium: point.equilibrium, velocity: point.velocity });
      }
    });
  }
  return choices;
}

/** `prefer`: the choice to show now (after a solve, its answer; after a sweep, its fastest
 * equilibrium, as the study shows it); else the current one is kept. */
function updateShapeChoices(prefer) {
  const select = $("shape-of");
  const previous = prefer ?? select.value;
  const choices = shapeChoices();
  select.replaceChildren(
    ...choices.map((choice) => {
      const option = document.createElement("option");
      option.value = choice.value;
      option.textContent = choice.label;
      return option;
    }),
  );
  if (choices.some((c) => c.value === previous)) select.value = previous;
  drawShape();
}

function drawShape() {
  const choice = shapeChoices().find((c) => c.value === $("shape-of").value);
  if (!choice) return;
  const raw = Number($("shape-scale").value);
  const scale = Number.isFinite(raw) && raw > 0 ? raw : 1;
  figures.drawShape(choice.wing, choice.equilibrium, `${f(choice.velocity, 2)} m/s`, scale);
  const t = choice.equilibrium.totals;
  const beyondModel = codesOf(choice.equilibrium.validity ?? []);
  $("shape-note").textContent =
    `At ${f(choice.velocity, 2)} m/s: tip twist ${signed(t.tip_twist, 2)} deg, tip heave ${f(t.tip_heave, 3)} m` +
    (scale === 1 ? " (true scale)." : `, drawn ${scale} times larger.`) +
    (beyondModel.length ? ` Beyond the model's validity: ${beyondModel.map(titleOf).join(", ").toLowerCase()}.` : "");
}

// --------------------------------------------------------------------------------- downloads

function downloadResults() {
  downloadJSON("flexwing-results.json", {
    solve: state.solve && {
      request: state.solve.request,
      response: state.solve.response,
      rigid: { note: state.solve.rigidNote, panels: state.solve.rigid.panels },
    },
    sweep: state.sweep,
    controls: state.controlRun,
    flutter: state.flutter,
  });
}

function downloadStations() {
  const s = state.solve.response.stations;
  const columns = [
    ["y [m]", s.y],
    ["heave [m]", s.heave],
    ["slope [-]", s.slope],
    ["twist [deg]", s.twist],
    ["shear [N]", s.shear],
    ["bending_moment [N m]", s.bending_moment],
    ["torque [N m]", s.torque],
  ];
  if (s.von_mises_stress) {
    columns.push(["bending_stress [Pa]", s.bending_stress], ["shear_stress [Pa]", s.shear_stress], ["von_mises_stress [Pa]", s.von_mises_stress]);
  }
  downloadText("flexwing-stations.csv", "text/csv", toCSV(columns));
}

function downloadPanels() {
  const p = state.solve.response.panels;
  const columns = [
    ["y [m]", p.y],
    ["lift [N]", p.lift],
    ["lift_per_span [N/m]", p.lift_per_span],
    ["torque [N m]", p.torque],
  ];
  if (state.solve.rigid) {
    columns.push(["rigid_y [m]", state.solve.rigid.panels.y], ["rigid_lift_per_span [N/m]", state.solve.rigid.panels.lift_per_span]);
  }
  downloadText("flexwing-panels.csv", "text/csv", toCSV(columns));
}

function downloadSweep() {
  const { response } = state.sweep;
  const kind = response.divergence.fit.amplification;
  const points = response.points;
  const total = (key) => points.map((p) => p.equilibrium?.totals[key] ?? null);
  const columns = [
    ["velocity [m/s]", points.map((p) => p.velocity)],
    ["status", points.map((p) => p.status)],
    ["lift [N]", total("lift")],
    ["rigid_lift [N]", total("rigid_lift")],
    ["lift_amplification [-]", total("lift_amplification")],
    ["alpha [deg]", total("alpha")],
    [`amplification_${kind} [-]`, points.map((p) => (p.equilibrium ? figures.amplification(p.equilibrium, kind) : null))],
    ["tip_twist [deg]", total("tip_twist")],
    ["tip_heave [m]", total("tip_heave")],
    ["root_bending_moment [N m]", total("root_bending_moment")],
    ["margin [-]", points.map((p) => p.equilibrium?.stability.margin ?? null)],
    ["validity", points.map((p) => (p.equilibrium ? codesOf(p.equilibrium.validity ?? []).join(" ") : null))],
    ["reason", points.map((p) => p.no_equilibrium?.reason ?? null)],
  ];
  downloadText("flexwing-sweep.csv", "text/csv", toCSV(columns));
}

/** Per airspeed, each surface's derivatives (in the unit the API gives), effectiveness and hinge moment. */
function downloadControls() {
  const { points, reversals } = state.controlRun.response;
  const columns = [
    ["velocity [m/s]", points.map((p) => p.velocity)],
    ["status", points.map((p) => p.status)],
  ];
  for (const { name } of reversals) {
    const of = (p) => p.controls.find((c) => c.name === name);
    const unit = points.map(of).find((c) => c)?.unit ?? "";
    const values = (key) => points.map((p) => of(p)?.[key] ?? null);
    columns.push(
      [`${name} derivative [${unit}]`, values("derivative")],
      [`${name} rigid_derivative [${unit}]`, values("rigid_derivative")],
      [`${name} effectiveness [-]`, values("effectiveness")],
      [`${name} hinge_moment [N m]`, values("hinge_moment")],
    );
  }
  columns.push(["reason", points.map((p) => p.no_equilibrium?.reason ?? null)]);
  downloadText("flexwing-controls.csv", "text/csv", toCSV(columns));
}

/** The V-g and V-f data: per airspeed, each mode's damping ratio and frequency. */
function downloadFlutter() {
  const { points, modes } = state.flutter.response;
  const columns = [
    ["velocity [m/s]", points.map((p) => p.velocity)],
    ["status", points.map((p) => p.status)],
    ["dynamic_pressure [Pa]", points.map((p) => p.dynamic_pressure)],
  ];
  modes.forEach((_, m) => {
    columns.push(
      [`mode ${m + 1} damping [-]`, points.map((p) => p.damping?.[m] ?? null)],
      [`mode ${m + 1} frequency [rad/s]`, points.map((p) => p.frequency?.[m] ?? null)],
    );
  });
  columns.push(["divergence_rate [1/s]", points.map((p) => p.divergence_rate ?? null)], ["reason", points.map((p) => p.reason ?? null)]);
  downloadText("flexwing-flutter.csv", "text/csv", toCSV(columns));
}

// ---------------------------------------------------------------------------------- JSON I/O

function jsonError(text) {
  $("json-error").textContent = text;
  $("json-error").hidden = !text;
}

function setControl(key, v) {
  if (v !== undefined && v !== null && state.controls[key]) state.controls[key].control.value = String(v);
}

function loadJSON(text) {
  jsonError("");
  let body;
  try {
    body = JSON.parse(text);
  } catch (error) {
    jsonError(`Not valid JSON: ${error.message}`);
    return;
  }
  const w = body?.wing ?? (Array.isArray(body?.y) ? body : null);
  if (!w || !Array.isArray(w.y)) {
    jsonError('No wing found: expected {"wing": {"y": [...], "chord": [...], ...}, "flight": {...}} or a wing.');
    return;
  }
  const known = new Set([...table.columns.map((c) => c.key), ...state.extra.map((e) => e.field.path?.replace("wing.", ""))]);
  // Control surfaces go into their table; a uniform mass model (three numbers) into its fields and
  // its concentrated masses into theirs; any other (per-station lists) is kept and sent as given.
  const surfaceList = Array.isArray(w.control_surfaces) && !$("surfaces-details").hidden ? w.control_surfaces : [];
  if (Array.isArray(w.control_surfaces) && !$("surfaces-details").hidden) known.add("control_surfaces");
  surfaces.fill(surfaceList);
  if (surfaceList.length) {
    $("surfaces-details").open = true;
    setControl("chordwise_panels", body.options?.chordwise_panels);
  }
  const mass = w.mass;
  const simpleMass =
    mass &&
    MASS_FIELDS.every((field) => typeof mass[field.path.split(".").at(-1)] === "number") &&
    (mass.concentrated == null || Array.isArray(mass.concentrated));
  if (simpleMass) {
    known.add("mass");
    for (const field of MASS_FIELDS) setControl(field.key, mass[field.path.split(".").at(-1)]);
  }
  concentrated.fill(simpleMass ? (mass.concentrated ?? []) : []);
  updateConcentrated();
  if (simpleMass && mass.concentrated?.length) $("concentrated-details").open = true;
  setMass(Boolean(simpleMass));
  // A tube spar of one diameter and one wall thickness goes into the spar's fields; any other
  // spar (per-station lists, a fraction of the thickness) is kept and sent as given.
  const spar = w.spar;
  const simpleSpar = spar && typeof spar.outer_diameter === "number" && typeof spar.wall_thickness === "number";
  if (simpleSpar) {
    known.add("spar");
    for (const field of SPAR_FIELDS) {
      if (field.path.startsWith("wing.")) setControl(field.key, field.path.split(".").slice(2).reduce((node, part) => node?.[part], spar));
    }
    setControl("safety_factor", body.options?.safety_factor);
  }
  // An optional field shows one number or string: a value it cannot (a camber table, a list per
  // station) is kept as given instead, and a field the body leaves out goes back to empty.
  const shown = (v) => typeof v === "string" || typeof v === "number";
  for (const { field } of state.extra) {
    const key = field.path?.replace("wing.", "");
    if (field.kind !== "column" && key in w && !shown(w[key])) known.delete(key);
  }
  state.passThrough = Object.fromEntries(Object.entries(w).filter(([k]) => !known.has(k)));
  for (const { field, control } of state.extra) {
    const v = field.path?.split(".").reduce((node, part) => node?.[part], { wing: w, flight: body.flight });
    if (field.kind === "column") {
      if (v !== undefined) control.value = String(v);
    } else {
      control.value = shown(v) ? String(v) : "";
    }
  }
  const { safety_factor: _, ...options } = body.options ?? {};
  state.options = options;
  setMode("table");
  table.fill(w);
  updateCount();
  updateSurfaces();
  const fl = body.flight ?? {};
  setStiffness(simpleSpar ? "spar" : "laws");
  setControl("velocity", fl.velocity);
  setControl("alpha", fl.alpha);
  setControl("density", fl.density);
  if (fl.weight !== undefined || fl.lift !== undefined) {
    // Trimmed; a lift to carry is a weight at load factor +-1.
    const lift = fl.lift;
    setControl("weight", fl.weight ?? Math.abs(lift));
    setControl("load_factor", fl.weight !== undefined ? (fl.load_factor ?? 1) : Math.sign(lift) || 1);
    setFlightMode("weight");
  } else if (fl.alpha !== undefined) {
    setFlightMode("alpha");
  }
  // A body's airspeeds go to the sweep; a wing with its mass (a /flutter body) also to flutter's.
  const v = body.velocities;
  for (const prefix of simpleMass ? ["sweep", "flutter"] : ["sweep"]) {
    if (Array.isArray(v) && v.length) {
      setControl(`${prefix}_start`, Math.min(...v));
      setControl(`${prefix}_stop`, Math.max(...v));
      setControl(`${prefix}_count`, v.length);
    } else if (v) {
      setControl(`${prefix}_start`, v.start);
      setControl(`${prefix}_stop`, v.stop);
      setControl(`${prefix}_count`, v.count);
    }
  }
  const extra = [...Object.keys(state.passThrough), ...Object.keys(state.options).map((k) => `options.${k}`)];
  $("planform-note").textContent =
    `Loaded a wing of ${table.rows} stations into the station table.` +
    (extra.length ? ` Kept as given (the editor has no field for them): ${extra.join(", ")}.` : "");
}

// ------------------------------------------------------------------------------------ wiring

async function exportFigure(button) {
  const figure = $(button.dataset.figure);
  const blob = await figures.figurePNG(figure);
  if (blob) downloadBlob(`flexwing-${button.dataset.figure.replace("fig-", "figure-")}.png`, blob);
}

function wire() {
  $("solve-form").addEventListener("submit", (event) => {
    event.preventDefault();
    runSolve();
  });
  $("sweep-form").addEventListener("submit", (event) => {
    event.preventDefault();
    runSweep();
  });
  $("cancel").addEventListener("click", () => state.abort?.abort());
  $("flutter-form").addEventListener("submit", (event) => {
    event.preventDefault();
    runFlutter();
  });
  $("controls-button").addEventListener("click", runControls);
  $("add-surface").addEventListener("click", () => {
    surfaces.addRow();
    updateSurfaces({ raise: true });
  });
  $("remove-surface").addEventListener("click", () => {
    surfaces.removeRow();
    updateSurfaces();
  });
  $("mass-on").addEventListener("change", () => setMass($("mass-on").checked));
  $("add-concentrated").addEventListener("click", () => {
    concentrated.append({ station: table.rows - 1 }); // at the tip, where a store flutters most
    updateConcentrated();
  });
  $("remove-concentrated").addEventListener("click", () => {
    concentrated.removeRow();
    updateConcentrated();
  });
  $("planform").addEventListener("input", () => state.mode === "planform" && regenerate());
  $("planform").addEventListener("change", () => state.mode === "planform" && regenerate());
  for (const radio of document.querySelectorAll('input[name="mode"]')) {
    radio.addEventListener("change", () => setMode(radio.value));
  }
  for (const radio of document.querySelectorAll('input[name="flight-mode"]')) {
    radio.addEventListener("change", () => setFlightMode(radio.value));
  }
  for (const radio of document.querySelectorAll('input[name="stiffness"]')) {
    radio.addEventListener("change", () => {
      delete state.passThrough.spar; // the user's choice replaces a spar loaded as given
      setStiffness(radio.value);
    });
  }
  $("add-row").addEventListener("click", () => {
    setMode("table");
    table.addRow();
    updateCount();
  });
  $("remove-row").addEventListener("click", () => {
    setMode("table");
    table.removeRow();
    updateCount();
  });
  $("json-load").addEventListener("click", () => loadJSON($("json-text").value));
  $("json-file").addEventListener("change", async () => {
    const file = $("json-file").files[0];
    if (file) loadJSON(await file.text());
  });
  $("json-download").addEventListener("click", () => downloadJSON("flexwing-wing.json", solveRequest()));
  $("download-json").addEventListener("click", downloadResults);
  $("download-stations").addEventListener("click", downloadStations);
  $("download-panels").addEventListener("click", downloadPanels);
  $("download-sweep").addEventListener("click", downloadSweep);
  $("download-controls").addEventListener("click", downloadControls);
  $("download-flutter").addEventListener("click", downloadFlutter);
  for (const button of document.querySelectorAll(".export-png")) {
    button.addEventListener("click", () => exportFigure(button));
  }
  $("shape-of").addEventListener("change", drawShape);
  $("shape-scale").addEventListener("input", drawShape);
}

async function main() {
  render(PLANFORM_FIELDS, $("planform"));
  render(FLIGHT_FIELDS, $("flight"));
  render(SWEEP_FIELDS, $("sweep"), { form: "sweep-form" });
  render(SPAR_FIELDS, $("spar"));
  render([CHORDWISE_FIELD], $("chordwise"));
  render(MASS_FIELDS, $("mass"));
  render(FLUTTER_FIELDS, $("flutter"), { form: "flutter-form" });
  for (const key of ["2", "3", "4", "5"]) figures.clear(`14.${key}`);
  for (const key of ["stress", "controls", "flutter"]) figures.clear(key);
  wire();
  installKeyBox(async () => {
    await runSolve();
    await runSweep();
  });
  setMode("planform");
  setFlightMode("alpha");
  setStiffness("laws");
  setMass(false);
  await addOptionalFields();
  updateSurfaces();
  // The study's wing, solved and swept as the page opens.
  await runSolve();
  await runSweep();
  window.__flexwing.ready = true;
  document.body.dataset.ready = "true";
}

main();
