// Request JSON in and out: a pasted or uploaded body of any operation (a POST /jobs body too:
// its request), or just a wing, loaded into the editor and the panels; the editor's wing and
// flight downloaded as a /solve body.
//
// The wing goes into the station table as the solver takes it: a wing whose station values are
// lists or single numbers goes in at once, any other form (`y` as {semispan, stations}) is
// expanded by the service (POST /wing/stations), never by a second implementation here. What
// no field shows is kept and sent as given (state.passThrough, .options, .kept, .keptFlight).

import * as api from "../api.js";
import { downloadJSON } from "../download.js";
import { $ } from "../dom.js";
import { setControl } from "../inputs.js";
import { showProblem } from "../problems.js";
import { allPanels } from "../registry.js";
import { schemas } from "../schema.js";
import { state } from "../state.js";
import { setBusy, setIdle } from "../status.js";
import { loadFlight } from "./flight.js";
import { editorRequest } from "./request.js";
import { surfaces } from "./surfaces.js";
import { loadWing, table, tableHolds } from "./wing.js";

const isObject = (v) => v !== null && typeof v === "object" && !Array.isArray(v);

/** Top-level keys the editor itself takes; the panels declare theirs (`takes`). */
const EDITOR_KEYS = ["wing", "flight", "velocities", "options"];

function jsonError(text) {
  $("json-error").textContent = text;
  $("json-error").hidden = !text;
}

/** The body's solver options: kept as given, but for the safety factor of a spar the spar's
 * fields show (then the field's, the API's default when the body has none). */
function loadOptions(options, simpleSpar) {
  const { safety_factor: safety, ...others } = options ?? {};
  if (simpleSpar) {
    setControl("safety_factor", safety ?? schemas().SolverOptions?.properties?.safety_factor?.default);
    state.options = others;
  } else {
    state.options = { ...options };
  }
}

/** Everything of `body` (its wing `w`, the station values `stations`) into the page. */
function apply(body, w, stations) {
  const request = w === body ? {} : body; // just a wing: no flight, options or airspeeds
  const notes = [];
  if (w) {
    const { simpleSpar } = loadWing(w, stations, request.options);
    loadOptions(request.options, simpleSpar);
    loadFlight(request.flight);
    notes.push(`Loaded a wing of ${table.rows} stations into the station table.`);
  }
  const claimed = new Set(EDITOR_KEYS);
  for (const panel of allPanels()) {
    for (const key of panel.takes ?? []) claimed.add(key);
    const note = panel.load?.(request);
    if (note) notes.push(note);
  }
  state.kept = Object.fromEntries(Object.entries(request).filter(([key]) => !claimed.has(key)));
  const shownOption = (k) => k === "chordwise_panels" && surfaces.rows > 0; // the surfaces' field
  const kept = [
    ...Object.keys(state.passThrough),
    ...Object.keys(state.options)
      .filter((k) => !shownOption(k))
      .map((k) => `options.${k}`),
    ...Object.keys(state.keptFlight).map((k) => `flight.${k}`),
    ...Object.keys(state.kept),
  ];
  if (kept.length) notes.push(`Kept as given (the editor has no field for them): ${kept.join(", ")}.`);
  $("planform-note").textContent = notes.join(" ");
  state.loads++;
}

/** The service's expansion of `w`'s stations, then the body into the page (busy meanwhile:
 * no run starts from the table before it is filled). */
async function expandThenApply(body, w) {
  setBusy("Reading the wing's stations");
  let stations;
  try {
    stations = await api.wingStations(w);
  } catch (error) {
    setIdle("The wing could not be read.");
    if (!(error instanceof api.ProblemError)) throw error;
    const reasons = (error.problem.errors ?? []).map((e) => `${e.field}: ${e.reason}`);
    jsonError(`The service could not read this wing: ${reasons.join("; ") || error.message}`);
    if (error.status === 401) showProblem(error);
    return;
  }
  apply(body, w, stations);
  setIdle(`Read the wing's ${stations.y.length} stations.`);
}

export function loadJSON(text) {
  jsonError("");
  let body;
  try {
    body = JSON.parse(text);
  } catch (error) {
    jsonError(`Not valid JSON: ${error.message}`);
    return;
  }
  // A POST /jobs body: its operation's request.
  if (isObject(body) && typeof body.operation === "string" && isObject(body.request)) body = body.request;
  const w = isObject(body?.wing) ? body.wing : isObject(body) && "y" in body ? body : null;
  // A body without a wing is loaded when a panel takes it (a batch's items).
  const taken = isObject(body) && allPanels().some((p) => p.takesBody?.(body));
  if (!w && !taken) {
    jsonError('No wing found: expected {"wing": {"y": [...], "chord": [...], ...}, "flight": {...}} or a wing.');
    return;
  }
  if (!w || tableHolds(w)) apply(body, w, w);
  else expandThenApply(body, w);
}

export function initLoad() {
  $("json-load").addEventListener("click", () => loadJSON($("json-text").value));
  $("json-file").addEventListener("change", async () => {
    const file = $("json-file").files[0];
    if (file) loadJSON(await file.text());
  });
  $("json-download").addEventListener("click", () => downloadJSON("flexwing-wing.json", editorRequest("solve", { withVelocity: true })));
}
