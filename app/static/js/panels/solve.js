// Solve: one equilibrium at the flight panel's condition (POST /solve): the totals, where the
// answer leaves the model's validity, Figures 14.2 and 14.3 (and the spar's stresses), and the
// stations' and strips' CSV.

import { toCSV, downloadText } from "../download.js";
import { $, f, MPa, signed } from "../dom.js";
import { editorRequest } from "../editor/request.js";
import { clear } from "../figures/chart.js";
import { drawLoads, drawStress } from "../figures/loads.js";
import { drawSpanwise } from "../figures/spanwise.js";
import { codesOf, findingItem, titleOf } from "../findings.js";
import { definePanel } from "../registry.js";
import { run } from "../run.js";
import { showShape } from "./shape.js";

const trimmed = (r) => r.totals.lift_effectiveness != null;
const withSpar = (r) => r.totals.failure_margin != null || r.totals.spar_mass != null;

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

// Findings about the spanwise figure's quantities are listed under it (their stations marked on
// its charts); the others (near divergence) next to the totals, beside the stability margin.
const SPANWISE_FINDINGS = new Set(["large_deflection", "large_twist", "section_stall"]);

/** The rigid wing's lift per span: the jig shape's own lattice solution at the same condition. */
const rigidOf = (response) => ({ panels: { y: response.panels.y, lift_per_span: response.panels.rigid_lift_per_span } });
const rigidNote = (response) =>
  "Rigid: the jig shape's own lattice solution at the same condition (panels.rigid_lift_per_span), " +
  `${f(response.totals.rigid_lift, 1)} N in all.`;

function renderTotals(request, response) {
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
  const { velocity, alpha, weight, lift, load_factor: n } = request.flight;
  const air = request.flight.altitude != null ? `${request.flight.altitude} m` : `${request.flight.density ?? 1.225} kg/m^3`;
  const trim = `(trimmed: alpha ${f(response.totals.alpha, 2)} deg), ${air}`;
  $("totals-condition").textContent =
    weight !== undefined
      ? `${velocity} m/s, weight ${weight} N${n !== undefined && n !== 1 ? ` × n ${n}` : ""} ${trim}`
      : lift !== undefined
        ? `${velocity} m/s, lift ${lift} N ${trim}`
        : `${velocity} m/s, alpha ${alpha} deg, ${air}`;
}

/** The spar's stresses under figure 14.3, when the answer has them; else the figure is hidden. */
function renderStress(request, response) {
  const spar = request.wing.spar;
  if (!response.stations.von_mises_stress || !spar) {
    clear("stress");
    $("fig-stress").hidden = true;
    return;
  }
  $("fig-stress").hidden = false;
  const safety = request.options?.safety_factor ?? 1;
  drawStress(response, spar.material.yield_stress, safety);
  const t = response.totals;
  const diameter = typeof spar.outer_diameter === "number" ? `${spar.outer_diameter} m` : "as given";
  const wall = typeof spar.wall_thickness === "number" ? `${spar.wall_thickness} m` : "as given";
  $("stress-note").textContent =
    `Tube D ${diameter}, wall ${wall}: ${f(t.spar_mass, 2)} kg for both halves; ` +
    `root bending stress ${MPa(t.root_bending_stress)}` +
    (t.rigid_root_bending_stress != null ? ` (rigid jig: ${MPa(t.rigid_root_bending_stress)})` : "") +
    `; failure margin ${signed(t.failure_margin, 2)} at safety factor ${safety}.`;
}

function renderValidity(response) {
  const findings = response.validity ?? [];
  const spanwise = findings.filter((x) => SPANWISE_FINDINGS.has(x.code));
  $("findings-14-2").replaceChildren(...spanwise.map(findingItem));
  $("findings-totals").replaceChildren(...findings.filter((x) => !SPANWISE_FINDINGS.has(x.code)).map(findingItem));
  $("validity").dataset.state = findings.length ? "findings" : "clear";
  $("validity-summary").textContent = findings.length
    ? `Beyond the model's validity: ${codesOf(findings).map(titleOf).join(", ").toLowerCase()}` +
      (spanwise.length ? " (stations marked in Figure 14.2, details under it)." : ".")
    : "Within the model's validity: deflection, twist, section lift coefficients and stability margin are all within their limits.";
}

function downloadStations(response) {
  const s = response.stations;
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

function downloadPanels(response) {
  const p = response.panels;
  const rigid = rigidOf(response).panels;
  const columns = [
    ["y [m]", p.y],
    ["lift [N]", p.lift],
    ["lift_per_span [N/m]", p.lift_per_span],
    ["torque [N m]", p.torque],
    ["rigid_y [m]", rigid.y],
    ["rigid_lift_per_span [N/m]", rigid.lift_per_span],
  ];
  downloadText("flexwing-panels.csv", "text/csv", toCSV(columns));
}

const solve = definePanel({
  name: "solve",
  operation: "solve",
  job: false,
  figures: ["14.2", "14.3", "stress"],
  init() {
    $("solve-form").addEventListener("submit", (event) => {
      event.preventDefault();
      run(solve);
    });
    $("download-stations").addEventListener("click", () => downloadStations(solve.last.response));
    $("download-panels").addEventListener("click", () => downloadPanels(solve.last.response));
  },
  request: () => editorRequest("solve", { withVelocity: true }),
  words: (request) => ({ busy: `Solving at ${request.flight.velocity} m/s`, failed: "Solve failed.", cancelled: "Solve cancelled." }),
  render({ request, response }) {
    renderTotals(request, response);
    $("rigid-note").textContent = rigidNote(response);
    drawSpanwise(response, rigidOf(response));
    drawLoads(response);
    renderStress(request, response);
    renderValidity(response);
    showShape("solve");
    for (const id of ["download-json", "download-stations", "download-panels"]) $(id).disabled = false;
    return `Solved at ${request.flight.velocity} m/s in ${(response.solver.seconds * 1000).toFixed(1)} ms of solver time.`;
  },
  results() {
    const last = solve.last;
    return last ? { ...last, rigid: { note: rigidNote(last.response), panels: rigidOf(last.response).panels } } : null;
  },
  equilibria() {
    const last = solve.last;
    if (!last) return [];
    const { velocity } = last.request.flight;
    return [{ value: "solve", label: `Solve: ${velocity} m/s`, wing: last.request.wing, equilibrium: last.response, velocity }];
  },
});
