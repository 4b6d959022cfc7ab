// The wing editor: planform numbers that fill the station table (or the table edited), the
// stiffness from EI/GJ laws or a tube spar, the optional fields this API version has, and the
// wing a request carries (always read from the table; what a loaded wing gives that no field
// shows is sent as given: state.passThrough).

import { $ } from "../dom.js";
import { controlValue, render, renderField, setControl, setPath, value } from "../inputs.js";
import { addResolver } from "../problems.js";
import { state } from "../state.js";
import { OPTIONAL_FIELDS, PLANFORM_FIELDS, SPAR_FIELDS, STIFFNESS_LAW_KEYS } from "./fields.js";
import { initMass, loadMass, massModel, mountMass } from "./mass.js";
import { StationTable, stationsFromPlanform } from "./stations.js";
import { initSurfaces, loadSurfaces, mountSurfaces, surfaces, updateSurfaces } from "./surfaces.js";

export let table = null;

function updateCount() {
  $("station-count").textContent = String(table.rows);
}

function regenerate() {
  table.fill(stationsFromPlanform(Object.fromEntries(PLANFORM_FIELDS.map((f) => [f.key, value(f.key)]))));
  updateCount();
}

export function setMode(mode) {
  state.mode = mode;
  $(`mode-${mode}`).checked = true;
  $("planform").disabled = mode === "table";
  $("planform-note").textContent =
    mode === "planform"
      ? "The station table follows these numbers."
      : 'The station table was edited or loaded, so the planform numbers no longer apply; choose "planform numbers" to fill the table from them again.';
  if (mode === "planform") regenerate();
}

/** Where EI and GJ come from: the laws (or the table's columns), or a tube spar. */
export function setStiffness(source) {
  state.stiffness = source;
  $(`stiffness-${source}`).checked = true;
  const spar = source === "spar";
  $("spar").hidden = !spar;
  for (const key of STIFFNESS_LAW_KEYS) state.controls[key].control.closest(".field").hidden = spar;
  $("stiffness-note").textContent = spar
    ? "EI and GJ follow from the tube (the station table's EI and GJ columns are not sent); the results add its stresses, failure margin and mass."
    : "";
}

/** The request's wing: the table, the spar or the laws' stiffness, surfaces, mass, optional
 * fields, and what a loaded wing keeps as given. */
export function wing() {
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
  const mass = massModel();
  if (mass) result.mass = mass;
  for (const { field, control } of state.extra) {
    if (field.path?.startsWith("wing.") && field.kind !== "column") {
      const v = controlValue(control, field.kind);
      if (v !== null && v !== "") setPath(result, field.path.slice("wing.".length), v);
    }
  }
  return result;
}

/** The options the wing's fields set: the safety factor of a spar's failure margin. */
export function sparOptions(options) {
  return state.stiffness === "spar" ? { ...options, safety_factor: value("safety_factor") } : options;
}

/** The controls that made a wing value (a 422's field): in planform mode the numbers that
 * generated it come first (focus goes there), then its cell or its column's header. */
function controlsOfWing(path, exact) {
  const match = /^wing\.(\w+)(?:\[(\d+)\])?/.exec(path);
  if (!match) return null;
  const [, list, index] = match;
  const found = [];
  if (state.mode === "planform") {
    for (const field of PLANFORM_FIELDS.filter((f) => f.feeds?.includes(list))) {
      const last = table.rows - 1;
      if (field.key === "root_chord" && index !== undefined && Number(index) === last && last > 0) continue;
      if (field.key === "tip_chord" && index !== undefined && Number(index) === 0) continue;
      found.push(state.controls[field.key].control);
    }
  }
  if (exact) found.push(exact);
  else found.push((index !== undefined ? $(`cell-${list}-${index}`) : null) ?? $(`col-${list}`));
  return found;
}

export function initWing() {
  render(PLANFORM_FIELDS, $("planform"));
  render(SPAR_FIELDS, $("spar"));
  table = new StationTable($("stations-table"), {
    onEdit: () => {
      if (state.mode !== "table") setMode("table");
      updateCount();
    },
  });
  initSurfaces();
  initMass(() => table.rows);
  addResolver(controlsOfWing);
  $("planform").addEventListener("input", () => state.mode === "planform" && regenerate());
  $("planform").addEventListener("change", () => state.mode === "planform" && regenerate());
  for (const radio of document.querySelectorAll('input[name="mode"]')) {
    radio.addEventListener("change", () => setMode(radio.value));
  }
  for (const radio of document.querySelectorAll('input[name="stiffness"]')) {
    radio.addEventListener("change", () => {
      delete state.passThrough.spar; // the user's choice replaces a spar loaded as given
      setStiffness(radio.value);
    });
  }
  for (const [id, edit] of [
    ["add-row", () => table.addRow()],
    ["remove-row", () => table.removeRow()],
  ]) {
    $(id).addEventListener("click", () => {
      setMode("table");
      edit();
      updateCount();
    });
  }
  setMode("planform");
  setStiffness("laws");
}

/** What the running API's wing has: the tube spar, surfaces, mass, and later fields (shown
 * when /openapi.json has them, their description as the hint; a "column" adds to the table). */
export function mountWing(schemas) {
  $("stiffness-from").hidden = !schemas.TubeSpar;
  mountSurfaces(schemas);
  mountMass(schemas);
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
  updateSurfaces();
}

/** Whether the table can hold the loaded wing's station values as they are (a list or one
 * number each); else the service expands them first (POST /wing/stations). */
export function tableHolds(w) {
  const fits = (v) => v === undefined || v === null || typeof v === "number" || Array.isArray(v);
  return Array.isArray(w.y) && table.columns.every((column) => fits(w[column.key]));
}

/** A loaded wing `w` into the editor; `stations`: its station values (w itself, or the
 * service's expansion of it); `options` the body's. Returns the wing keys kept as given. */
export function loadWing(w, stations, options) {
  const known = new Set([...table.columns.map((c) => c.key), ...state.extra.map((e) => e.field.path?.replace("wing.", ""))]);
  // Control surfaces go into their table; a uniform mass model (three numbers) into its fields and
  // its concentrated masses into theirs; any other (per-station lists) is kept and sent as given.
  if (loadSurfaces(w, options)) known.add("control_surfaces");
  if (loadMass(w)) known.add("mass");
  // A tube spar of one diameter and one wall thickness goes into the spar's fields; any other
  // spar (per-station lists, a fraction of the thickness) is kept and sent as given.
  const spar = w.spar;
  const simpleSpar = spar && typeof spar.outer_diameter === "number" && typeof spar.wall_thickness === "number";
  if (simpleSpar) {
    known.add("spar");
    for (const field of SPAR_FIELDS) {
      if (field.path.startsWith("wing.")) setControl(field.key, field.path.split(".").slice(2).reduce((node, part) => node?.[part], spar));
    }
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
    const v = field.path?.split(".").reduce((node, part) => node?.[part], { wing: w });
    if (field.kind === "column") {
      if (v !== undefined) control.value = String(v);
    } else if (field.path?.startsWith("wing.")) {
      control.value = shown(v) ? String(v) : "";
    }
  }
  setMode("table");
  table.fill(stations);
  updateCount();
  updateSurfaces();
  setStiffness(simpleSpar ? "spar" : "laws");
  return { simpleSpar: Boolean(simpleSpar), kept: Object.keys(state.passThrough) };
}
