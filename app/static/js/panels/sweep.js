// Sweep: the same wing and flight over airspeeds (POST /jobs, operation sweep): Figure 14.4,
// the sweep's points as a table, from which airspeed on the model's validity ends, the CSV.
// Its airspeeds are also the controls' (panels/controls.js).

import { downloadText, toCSV } from "../download.js";
import { $, f, signed } from "../dom.js";
import { Airspeeds } from "../editor/airspeeds.js";
import { editorRequest } from "../editor/request.js";
import { AMPLIFICATION_WORDS, amplification, drawSweep } from "../figures/sweep.js";
import { codesOf, SHORT_FINDINGS } from "../findings.js";
import { definePanel } from "../registry.js";
import { run } from "../run.js";
import { showShape } from "./shape.js";

/** The sweep's airspeeds (the controls run at them too). */
export let airspeeds = null;

const COLUMNS = [
  ["V [m/s]", (p) => f(p.velocity, 2)],
  ["status", (p) => p.status.replace("_", " ")],
  ["lift [N]", (p) => f(p.equilibrium?.totals.lift, 1)],
  ["L / L_rigid", (p) => f(p.equilibrium?.totals.lift_amplification, 3), "alpha"],
  ["alpha [deg]", (p) => f(p.equilibrium?.totals.alpha, 2), "trimmed"],
  ["lift effectiveness", (p) => f(p.equilibrium?.totals.lift_effectiveness, 3), "trimmed"],
  ["tip twist [deg]", (p) => signed(p.equilibrium?.totals.tip_twist, 2)],
  ["tip heave [m]", (p) => f(p.equilibrium?.totals.tip_heave, 3)],
  ["margin", (p) => f(p.equilibrium?.stability.margin, 3)],
  ["beyond the model", (p) => (p.equilibrium ? codesOf(p.equilibrium.validity ?? []).map((c) => SHORT_FINDINGS[c] ?? c).join(", ") || "-" : "")],
];

function notesOf({ fit, linear, fold }) {
  const notes = [];
  if (fit.velocity != null) {
    notes.push(
      `Dashed: the study's fit 1/A = ${f(fit.intercept, 3)} ${fit.slope < 0 ? "-" : "+"} ${Math.abs(fit.slope).toExponential(3)} q over ${fit.points_used} stable points ` +
        `(A = ${AMPLIFICATION_WORDS[fit.amplification] ?? fit.amplification}), drawn to 92 % of its V_div ${f(fit.velocity, 2)} m/s.`,
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
  return notes.join(" ");
}

function renderTable(request, response) {
  const mode = request.flight.alpha !== undefined ? "alpha" : "trimmed";
  const columns = COLUMNS.filter(([, , only]) => !only || only === mode);
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

function downloadSweep(response) {
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
    [`amplification_${kind} [-]`, points.map((p) => (p.equilibrium ? amplification(p.equilibrium, kind) : null))],
    ["tip_twist [deg]", total("tip_twist")],
    ["tip_heave [m]", total("tip_heave")],
    ["root_bending_moment [N m]", total("root_bending_moment")],
    ["margin [-]", points.map((p) => p.equilibrium?.stability.margin ?? null)],
    ["validity", points.map((p) => (p.equilibrium ? codesOf(p.equilibrium.validity ?? []).join(" ") : null))],
    ["reason", points.map((p) => p.no_equilibrium?.reason ?? null)],
  ];
  downloadText("flexwing-sweep.csv", "text/csv", toCSV(columns));
}

const sweep = definePanel({
  name: "sweep",
  operation: "sweep",
  job: true,
  figures: ["14.4"],
  init() {
    airspeeds = new Airspeeds("sweep", $("sweep"), { start: 4, stop: 22, count: 10 }, { form: "sweep-form" });
    $("sweep-form").addEventListener("submit", (event) => {
      event.preventDefault();
      run(sweep);
    });
    $("download-sweep").addEventListener("click", () => downloadSweep(sweep.last.response));
  },
  /** A body's airspeeds go to the sweep (a flutter body's to flutter's too). */
  load(body) {
    airspeeds.load(body.velocities);
  },
  request: () => ({ ...editorRequest("sweep", { withVelocity: false }), velocities: airspeeds.read() }),
  words: () => ({ busy: "Sweeping", failed: "Sweep failed.", cancelled: "Sweep cancelled." }),
  render({ request, response }) {
    drawSweep(response);
    $("sweep-note").textContent = notesOf(response.divergence);
    renderTable(request, response);
    renderOnsets(response);
    const fastest = response.points.findLastIndex((p) => p.status === "equilibrium");
    showShape(fastest >= 0 ? `sweep-${fastest}` : undefined);
    $("download-sweep").disabled = false;
    $("download-json").disabled = false;
    const solved = response.points.filter((p) => p.status === "equilibrium").length;
    return `Swept ${response.points.length} airspeeds: ${solved} equilibria.`;
  },
  results: () => sweep.last ?? null,
  equilibria() {
    if (!sweep.last) return [];
    const { request, response } = sweep.last;
    return response.points.flatMap((point, i) =>
      point.status === "equilibrium"
        ? [{ value: `sweep-${i}`, label: `Sweep: ${f(point.velocity, 2)} m/s`, wing: request.wing, equilibrium: point.equilibrium, velocity: point.velocity }]
        : [],
    );
  },
});
