// The wing's control surfaces (flaps and ailerons), one row each: wing.control_surfaces, and the
// chordwise panels they need (options.chordwise_panels). Panels that need surfaces (controls,
// roll) hear of their count: announce("surfaces", n).

import { $ } from "../dom.js";
import { applyLimits, render, setControl, value } from "../inputs.js";
import { announce } from "../registry.js";
import { schemas } from "../schema.js";
import { state } from "../state.js";
import { CHORDWISE_FIELD, CONTROL_SURFACE_COLUMNS, panelsForHinge } from "./fields.js";
import { RowTable } from "./rows.js";

export class ControlSurfaceTable extends RowTable {
  constructor(table, { onChange } = {}) {
    super(table, { columns: CONTROL_SURFACE_COLUMNS, path: "wing.control_surfaces", id: "surface", onChange });
  }

  /** Add a surface: the study's aileron first, then a flap inboard of it, then copies. */
  addRow() {
    const surfaces = this.read();
    const defaults = Object.fromEntries(CONTROL_SURFACE_COLUMNS.map((c) => [c.key, c.value]));
    const taken = new Set(surfaces.map((s) => s.name));
    let next = defaults;
    if (taken.has("aileron")) next = { ...defaults, name: "flap", kind: "flap", start: 0, end: 0.45, hinge: 0.5 };
    for (let n = 2; taken.has(next.name); n++) next = { ...next, name: `${next.kind}-${n}` };
    this.append(next);
  }
}

export let surfaces = null;

/** The surfaces' count, the chordwise panels they need, and the panels that need surfaces. */
export function updateSurfaces({ raise = false } = {}) {
  const n = surfaces.rows;
  $("surface-count").textContent = n ? String(n) : "none";
  $("chordwise").hidden = n === 0;
  announce("surfaces", n);
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

export function initSurfaces() {
  surfaces = new ControlSurfaceTable($("surfaces-table"), { onChange: () => updateSurfaces() });
  render([CHORDWISE_FIELD], $("chordwise"));
  $("add-surface").addEventListener("click", () => {
    surfaces.addRow();
    updateSurfaces({ raise: true });
  });
  $("remove-surface").addEventListener("click", () => {
    surfaces.removeRow();
    updateSurfaces();
  });
}

/** Offered when the running API has control surfaces. */
export function mountSurfaces(schemas) {
  const schema = schemas.Wing?.properties?.control_surfaces && schemas.ControlSurface;
  $("surfaces-details").hidden = !schema;
  if (schema) surfaces.setSchema(schema);
  applyLimits(state.controls.chordwise_panels.control, schemas.SolverOptions?.properties?.chordwise_panels);
}

/** The surfaces of a loaded wing into the table (none: emptied); whether they were taken. */
export function loadSurfaces(wing, options) {
  const offered = Array.isArray(wing.control_surfaces) && !$("surfaces-details").hidden;
  const list = offered ? wing.control_surfaces : [];
  surfaces.fill(list);
  if (list.length) {
    $("surfaces-details").open = true;
    const byDefault = schemas().SolverOptions?.properties?.chordwise_panels?.default;
    setControl("chordwise_panels", options?.chordwise_panels ?? byDefault);
  }
  return offered;
}

/** options.chordwise_panels of a request whose wing has surfaces. */
export function withChordwise(request) {
  if (request.wing.control_surfaces?.length) {
    request.options = { ...request.options, [CHORDWISE_FIELD.path.split(".")[1]]: value(CHORDWISE_FIELD.key) };
  }
  return request;
}
