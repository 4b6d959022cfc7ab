// Every input of the wing and flight editor is described here, once: label, unit, default and
// where its value goes (a panel describes its own: panels/*.js). Adding a field the API gains
// later is one entry in one of these lists (see OPTIONAL_FIELDS). inputs.js renders them.
//
// A descriptor has:
//   key     a name unique on the page (the input's id is "f-" + key)
//   path    where the value goes in a request body ("flight.velocity"); the error of that path
//           in a 422 problem is shown next to the input. Planform fields have no path: they
//           generate the station table, and `feeds` names the wing lists they generate.
//   label, unit, hint   shown to the user; every input has a <label>.
//   kind    "number" (default), "integer", "select", "text" or "flag"; `options` for a select.
//   value   the default: the design study's wing and flight (shared/seed, chapter 14).

export const PLANFORM_FIELDS = [
  { key: "span", label: "Span, tip to tip", unit: "m", value: 10, feeds: ["y"] },
  { key: "n", label: "Stations N (half-wing)", unit: "-", kind: "integer", value: 30, feeds: ["y"] },
  { key: "root_chord", label: "Root chord", unit: "m", value: 1.414213562, feeds: ["chord"] },
  { key: "tip_chord", label: "Tip chord", unit: "m", value: 0.1414213562, feeds: ["chord"] },
  {
    key: "taper",
    label: "Taper law",
    kind: "select",
    value: "sqrt",
    options: [
      ["sqrt", "study's: c = sqrt(linspace(c_root^2, c_tip^2, N))"],
      ["linear", "linear: c = linspace(c_root, c_tip, N)"],
    ],
    feeds: ["chord"],
  },
  {
    key: "elastic_axis",
    label: "Elastic axis",
    unit: "fraction of chord from the LE",
    value: 0.4,
    feeds: ["elastic_axis"],
  },
  {
    key: "ei_law",
    label: "Bending stiffness law",
    kind: "select",
    value: "cubic",
    options: [
      ["cubic", "EI = k c^3"],
      ["constant", "EI = k"],
    ],
    feeds: ["bending_stiffness"],
  },
  { key: "ei_k", label: "EI coefficient k", unit: "N m^2 (per m^3 of c^3)", value: 2e4, feeds: ["bending_stiffness"] },
  {
    key: "gj_law",
    label: "Torsional stiffness law",
    kind: "select",
    value: "cubic",
    options: [
      ["cubic", "GJ = k c^3"],
      ["constant", "GJ = k"],
    ],
    feeds: ["torsional_stiffness"],
  },
  { key: "gj_k", label: "GJ coefficient k", unit: "N m^2 (per m^3 of c^3)", value: 1e3, feeds: ["torsional_stiffness"] },
];

// Columns of the station table: one list of N values each in `wing`.
export const STATION_COLUMNS = [
  { key: "y", label: "y", unit: "m" },
  { key: "chord", label: "chord", unit: "m" },
  { key: "elastic_axis", label: "elastic axis", unit: "x/c", scalarWhenUniform: true },
  { key: "bending_stiffness", label: "EI", unit: "N m^2" },
  { key: "torsional_stiffness", label: "GJ", unit: "N m^2" },
];

// `flightMode`: shown and sent only when the flight panel's choice ("Fly at") is that mode: at an
// angle of attack (FlightAtAlpha), or trimmed to carry a weight (FlightAtWeight) or a lift
// (FlightAtLift), the angle of attack solved for. A request carries exactly one of alpha,
// weight (+ load_factor) and lift. An `optional` field left empty is not sent: the request
// carries what the user gave (a loaded flight's own keys), the API's default the rest (a
// load factor of 1: none given; a flight at an altitude has no density).

export const FLIGHT_FIELDS = [
  { key: "velocity", path: "flight.velocity", label: "Airspeed", unit: "m/s", value: 10, solveOnly: true, optional: true },
  { key: "alpha", path: "flight.alpha", label: "Angle of attack", unit: "deg", value: 5, flightMode: "alpha" },
  {
    key: "weight",
    path: "flight.weight",
    label: "Weight",
    unit: "N",
    value: 300,
    flightMode: "weight",
  },
  {
    key: "load_factor",
    path: "flight.load_factor",
    label: "Load factor",
    unit: "-",
    value: null,
    placeholder: "1 (level flight)",
    flightMode: "weight",
    optional: true,
  },
  { key: "lift", path: "flight.lift", label: "Lift of both halves", unit: "N", value: 300, flightMode: "lift" },
  { key: "density", path: "flight.density", label: "Air density", unit: "kg/m^3", value: 1.225, placeholder: "1.225 (sea level)", optional: true },
];

// A circular tube spar (TubeSpar): EI and GJ follow from it instead of the EI/GJ laws or the
// table's columns, and the answer adds stresses, failure margin and spar mass. Prefilled: a
// carbon-fibre tube (SparMaterial's example numbers) that carries the study's wing at 10 m/s.
export const SPAR_FIELDS = [
  { key: "spar_outer_diameter", path: "wing.spar.outer_diameter", label: "Outer diameter D", unit: "m", value: 0.05 },
  { key: "spar_wall_thickness", path: "wing.spar.wall_thickness", label: "Wall thickness t", unit: "m", value: 0.002 },
  { key: "spar_youngs_modulus", path: "wing.spar.material.youngs_modulus", label: "Young's modulus E", unit: "Pa", value: 7e10 },
  { key: "spar_shear_modulus", path: "wing.spar.material.shear_modulus", label: "Shear modulus G", unit: "Pa", value: 2.7e10 },
  { key: "spar_yield_stress", path: "wing.spar.material.yield_stress", label: "Yield stress", unit: "Pa", value: 6e8 },
  { key: "spar_density", path: "wing.spar.material.density", label: "Material density", unit: "kg/m^3", value: 1600 },
  { key: "safety_factor", path: "options.safety_factor", label: "Safety factor", unit: "-", value: 1.5 },
];

// The planform fields that describe EI and GJ: not used (hidden) when the stiffness comes from the spar.
export const STIFFNESS_LAW_KEYS = ["ei_law", "ei_k", "gj_law", "gj_k"];

// Fields later API versions may add. Each is shown only when the running server's OpenAPI
// document (/openapi.json) has `property` in components.schemas[`schema`]; its description
// there becomes the hint. A "column" field adds a column to the station table instead. A group
// is one entry per member with a nested path ("wing.<group>.<member>"): setPath builds the
// object. (The tube spar has its own fields, SPAR_FIELDS, behind the "Stiffness from" choice.)
export const OPTIONAL_FIELDS = [
  { key: "sweep_angle", schema: "Wing", property: "sweep", path: "wing.sweep", label: "Sweep", unit: "deg", value: 0 },
  { key: "airfoil", schema: "Wing", property: "airfoil", path: "wing.airfoil", label: "Airfoil", kind: "text", value: "" },
  { key: "jig_twist", schema: "Wing", property: "jig_twist", path: "wing.jig_twist", label: "jig twist", unit: "deg", kind: "column", value: 0 },
];

// Control surfaces (wing.control_surfaces, ControlSurface): one row each in the surfaces table.
// `schema` names the ControlSurface property whose description and limits the column takes from
// /openapi.json. The default row is the study's aileron (shared/seed).
export const CONTROL_SURFACE_COLUMNS = [
  { key: "name", label: "name", unit: "", kind: "text", value: "aileron" },
  { key: "start", label: "start", unit: "b/2 or m", value: 0.55 },
  { key: "end", label: "end", unit: "b/2 or m", value: 0.95 },
  {
    key: "extent_unit",
    label: "extent in",
    unit: "",
    kind: "select",
    value: "fraction",
    options: [
      ["fraction", "b/2"],
      ["m", "m"],
    ],
  },
  { key: "hinge", label: "hinge", unit: "x/c", value: 0.75 },
  { key: "deflection", label: "deflection", unit: "deg, TE down", value: 5 },
  {
    key: "kind",
    label: "kind",
    unit: "",
    kind: "select",
    value: "aileron",
    options: [
      ["aileron", "aileron"],
      ["flap", "flap"],
    ],
  },
];

// With control surfaces the lattice needs panels aft of each hinge: options.chordwise_panels.
export const CHORDWISE_FIELD = {
  key: "chordwise_panels",
  path: "options.chordwise_panels",
  label: "Chordwise panels per strip",
  unit: "-",
  kind: "integer",
  value: 4,
};

/** The chordwise panels a hinge at `hinge` (fraction of chord) needs: a whole cosine-spaced panel
 * aft of it (the interior nodes of k panels are at (1 - cos(pi i / k)) / 2). */
export function panelsForHinge(hinge) {
  for (let k = 2; k <= 8; k++) {
    const last = (1 - Math.cos((Math.PI * (k - 1)) / k)) / 2;
    if (hinge <= last + 1e-12) return k;
  }
  return 8;
}

// The wing's mass model (wing.mass, MassModel), needed by POST /flutter (others ignore it). The
// defaults are the light mass of the study's wing in the flutter examples ("study_loaded").
export const MASS_FIELDS = [
  { key: "mass_per_length", path: "wing.mass.mass_per_length", label: "Mass per length", unit: "kg/m", value: 1.0 },
  { key: "center_of_gravity", path: "wing.mass.center_of_gravity", label: "Centre of gravity", unit: "fraction of chord from the LE", value: 0.42 },
  { key: "inertia_per_length", path: "wing.mass.inertia_per_length", label: "Inertia per length (about the CG)", unit: "kg m", value: 0.02 },
];

// wing.mass.concentrated: a store, an engine or a balance weight at a station (new rows at the tip).
export const CONCENTRATED_MASS_COLUMNS = [
  { key: "station", label: "station", unit: "index, 0 = root", kind: "integer", value: null },
  { key: "mass", label: "mass", unit: "kg", value: 1 },
  { key: "inertia", label: "inertia (about its CG)", unit: "kg m^2", value: 0 },
  { key: "offset", label: "CG aft of the elastic axis", unit: "m", value: 0 },
];
