// The flight panel: fly at an angle of attack, or trimmed to carry a weight (times a load
// factor) or a lift; the airspeed (one operation's: a sweep's airspeeds are its own) and the
// air density. A loaded flight's keys the chosen mode does not show (a design's fixed alpha
// beside its weight) are kept and sent to the operations whose flight takes them.

import { $ } from "../dom.js";
import { controlValue, render, resetControl, setControl, setPath, value } from "../inputs.js";
import { flightTakes } from "../schema.js";
import { state } from "../state.js";
import { FLIGHT_FIELDS } from "./fields.js";

/** What "same ..." says of each mode under the airspeed panels' legends. */
const SAME = { alpha: "angle of attack", weight: "weight, load factor", lift: "lift" };

/** The flight panel's choice: at an angle of attack, or trimmed to a weight or a lift. */
export function setFlightMode(mode) {
  state.flightMode = mode;
  $(`flight-mode-${mode}`).checked = true;
  for (const wrap of $("flight").querySelectorAll(".field[data-flight-mode]")) {
    wrap.hidden = wrap.dataset.flightMode !== mode;
  }
  for (const element of document.querySelectorAll(".flight-same")) element.textContent = SAME[mode];
}

/** The request's flight for `operation`: the fields of the chosen mode (the airspeed only
 * `withVelocity`), optional flight fields, and the loaded keys its flight takes. */
export function flight(operation, { withVelocity }) {
  const result = {};
  for (const field of FLIGHT_FIELDS) {
    if (field.solveOnly && !withVelocity) continue;
    if (field.flightMode && field.flightMode !== state.flightMode) continue;
    const v = value(field.key);
    if (field.optional && v === null) continue; // left empty: not sent (the API's default)
    setPath(result, field.path, v);
  }
  result.flight ??= {};
  for (const { field, control } of state.extra) {
    if (field.path?.startsWith("flight.")) {
      const v = controlValue(control, field.kind);
      if (v !== null && v !== "") setPath(result, field.path, v);
    }
  }
  for (const [key, v] of Object.entries(state.keptFlight)) {
    if (flightTakes(operation, state.flightMode, key)) result.flight[key] = v;
  }
  return result.flight;
}

export function initFlight() {
  render(FLIGHT_FIELDS, $("flight"));
  for (const radio of document.querySelectorAll('input[name="flight-mode"]')) {
    radio.addEventListener("change", () => {
      state.keptFlight = {}; // the user's choice replaces what a loaded flight kept
      setFlightMode(radio.value);
    });
  }
  setFlightMode("alpha");
}

/** Trim and a lift to carry came with later API versions: offered when this one has them. */
export function mountFlight(schemas) {
  $("flight-mode").hidden = !schemas.FlightAtWeight;
  $("flight-mode-lift").closest("label").hidden = !schemas.FlightAtLift;
}

/** A loaded flight into the fields: its way (alpha, weight or lift) chooses the mode, whose
 * fields it leaves out go back to their defaults (the API's), as does the density; the
 * airspeed, which a sweep's body does not have, stays. A body without a flight (a bare wing)
 * leaves the panel as it is. */
export function loadFlight(fl) {
  state.keptFlight = {};
  if (!fl) return;
  const mode = ["lift", "weight", "alpha"].find((way) => way in fl);
  // An equivalent airspeed or an altitude replaces the field it excludes (both: a 422).
  if (fl.equivalent_airspeed != null && fl.velocity == null) $("f-velocity").value = "";
  else setControl("velocity", fl.velocity);
  if (mode) {
    for (const field of FLIGHT_FIELDS.filter((f) => f.flightMode === mode)) resetControl(field.key, fl[field.key]);
    setFlightMode(mode);
  }
  if (fl.altitude != null && fl.density == null) $("f-density").value = "";
  else resetControl("density", fl.density);
  const shown = new Set(["velocity", "density", ...FLIGHT_FIELDS.filter((f) => f.flightMode === state.flightMode).map((f) => f.key)]);
  state.keptFlight = Object.fromEntries(Object.entries(fl).filter(([key]) => !shown.has(key)));
}
