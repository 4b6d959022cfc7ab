// The wing's mass model (wing.mass, for flutter): uniform mass, centre of gravity and inertia
// along the span, and concentrated masses at stations (a store, an engine, a balance weight).

import { $ } from "../dom.js";
import { applyLimits, render, setControl, setPath, value } from "../inputs.js";
import { state } from "../state.js";
import { CONCENTRATED_MASS_COLUMNS, MASS_FIELDS } from "./fields.js";
import { RowTable } from "./rows.js";

let concentrated = null;

function updateConcentrated() {
  $("concentrated-count").textContent = concentrated.rows ? String(concentrated.rows) : "none";
}

export function setMass(on) {
  state.mass = on;
  $("mass-on").checked = on;
  $("mass").hidden = !on;
  $("concentrated-details").hidden = !on;
  $("flutter-hint").textContent = on
    ? "Enter in a flutter field runs it."
    : 'Needs the wing\'s mass: tick "the wing has a mass model" under Wing.';
}

/** `stationCount()`: the wing's stations now (a new concentrated mass goes to the tip). */
export function initMass(stationCount) {
  render(MASS_FIELDS, $("mass"));
  concentrated = new RowTable($("concentrated-table"), {
    columns: CONCENTRATED_MASS_COLUMNS,
    path: "wing.mass.concentrated",
    id: "concentrated",
    onChange: () => updateConcentrated(),
  });
  $("mass-on").addEventListener("change", () => setMass($("mass-on").checked));
  $("add-concentrated").addEventListener("click", () => {
    concentrated.append({ station: stationCount() - 1 }); // at the tip, where a store flutters most
    updateConcentrated();
  });
  $("remove-concentrated").addEventListener("click", () => {
    concentrated.removeRow();
    updateConcentrated();
  });
  setMass(false);
}

/** Offered (with flutter) when the running API has the mass model and POST /flutter. */
export function mountMass(schemas) {
  const massSchema = schemas.Wing?.properties?.mass && schemas.MassModel;
  $("mass-from").hidden = !(massSchema && schemas.FlutterRequest);
  for (const field of MASS_FIELDS) {
    const property = massSchema?.properties?.[field.path.split(".").at(-1)];
    const { control } = state.controls[field.key];
    applyLimits(control, property);
    if (property?.description) control.title = property.description;
  }
  if (schemas.ConcentratedMass) concentrated.setSchema(schemas.ConcentratedMass);
}

/** wing.mass from the fields and the table, or undefined without a mass model. */
export function massModel() {
  if (!state.mass) return undefined;
  const mass = {};
  for (const field of MASS_FIELDS) setPath(mass, field.path, value(field.key));
  if (concentrated.rows) mass.wing.mass.concentrated = concentrated.read();
  return mass.wing.mass;
}

/** Whether the wing has a mass model: in the fields, or loaded and kept as given. */
export const hasMass = () => state.mass || state.passThrough.mass != null;

/** A loaded wing's mass: a uniform model (three numbers) and its concentrated masses go into
 * the fields and the table; whether it was taken (else it is sent as given). */
export function loadMass(wing) {
  const mass = wing.mass;
  const simple =
    mass != null &&
    MASS_FIELDS.every((field) => typeof mass[field.path.split(".").at(-1)] === "number") &&
    (mass.concentrated == null || Array.isArray(mass.concentrated));
  if (simple) for (const field of MASS_FIELDS) setControl(field.key, mass[field.path.split(".").at(-1)]);
  concentrated.fill(simple ? (mass.concentrated ?? []) : []);
  updateConcentrated();
  if (simple && mass.concentrated?.length) $("concentrated-details").open = true;
  setMass(Boolean(simple));
  if (mass != null && !simple) $("flutter-hint").textContent = "The loaded wing's mass model is sent as given.";
  return Boolean(simple);
}
