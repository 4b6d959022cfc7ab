// The answer of a sizing run (POST /loads) as a table and files: a row per case (its flight,
// status, root loads and why it has none) under the V-n figure, and the CSVs of the envelope
// along the span (each extreme with its case) and of the cases.

import { downloadText, toCSV } from "../download.js";
import { $, el, f } from "../dom.js";

const shortStatus = (c) => (c.status === "equilibrium" ? "loads" : c.status.replaceAll("_", " "));

const CASE_COLUMNS = [
  ["#", (c, i) => String(i)],
  ["name", (c) => c.name],
  ["kind", (c) => c.kind],
  ["EAS [m/s]", (c) => f(c.equivalent_airspeed, 2)],
  ["V [m/s]", (c) => f(c.velocity, 2)],
  ["weight [N]", (c) => f(c.weight, 1)],
  ["n [-]", (c) => f(c.load_factor, 3)],
  ["alpha [deg]", (c) => f(c.alpha, 2)],
  ["status", shortStatus],
  ["root shear [N]", (c) => f(c.shear?.[0], 1)],
  ["root bending moment [N·m]", (c) => f(c.bending_moment?.[0], 1)],
  ["root torque [N·m]", (c) => f(c.torque?.[0], 2)],
  ["tip twist [deg]", (c) => f(c.tip_twist, 2)],
  ["why no loads", (c) => c.reason ?? ""],
];

export function renderCases(response) {
  const table = $("vn-table");
  table.tHead.replaceChildren(el("tr", {}, ...CASE_COLUMNS.map(([label]) => el("th", { scope: "col" }, label))));
  table.tBodies[0].replaceChildren(
    ...response.cases.map((c, i) => {
      const row = el("tr", { data: { status: c.status, case: c.name }, title: c.reason ?? undefined });
      for (const [, format] of CASE_COLUMNS) row.append(el("td", {}, format(c, i)));
      return row;
    }),
  );
}

/** The envelope along the span: per station the extremes and the case giving each. */
export function downloadEnvelope(response) {
  const env = response.envelope;
  const name = (i) => response.cases[i]?.name ?? null;
  const columns = [["y [m]", env.y]];
  for (const [key, unit] of [
    ["shear", "N"],
    ["bending_moment", "N m"],
    ["torque", "N m"],
  ]) {
    for (const side of ["max", "min"]) {
      columns.push([`${side}_${key} [${unit}]`, env[`${side}_${key}`]], [`${side}_${key}_case`, env[`${side}_${key}_case`].map(name)]);
    }
  }
  downloadText("flexwing-loads-envelope.csv", "text/csv", toCSV(columns));
}

/** Each case: its flight, status and root loads. */
export function downloadCases(response) {
  const columns = ["name", "kind", "status", "equivalent_airspeed", "velocity", "density", "weight", "load_factor", "alpha", "tip_heave", "tip_twist", "reason"].map((key) => [key, response.cases.map((c) => c[key] ?? null)]);
  for (const key of ["shear", "bending_moment", "torque"]) columns.push([`root_${key}`, response.cases.map((c) => c[key]?.[0] ?? null)]);
  downloadText("flexwing-load-cases.csv", "text/csv", toCSV(columns));
}
