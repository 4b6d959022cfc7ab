// Control effectiveness: each control surface's elastic over rigid derivative against airspeed
// at the sweep's airspeeds, its reversal and the wing's divergence speeds (POST /jobs,
// operation controls); offered while the wing has control surfaces.

import { downloadText, toCSV } from "../download.js";
import { $, f, plural } from "../dom.js";
import { editorRequest } from "../editor/request.js";
import { surfaces } from "../editor/surfaces.js";
import { drawControls } from "../figures/controls.js";
import { definePanel } from "../registry.js";
import { run } from "../run.js";
import { airspeeds } from "./sweep.js";

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

/** Per airspeed, each surface's derivatives (in the unit the API gives), effectiveness and hinge moment. */
function downloadControls(response) {
  const { points, reversals } = response;
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

const controls = definePanel({
  name: "controls",
  operation: "controls",
  job: true,
  figures: ["controls"],
  init() {
    $("controls-button").addEventListener("click", () => run(controls));
    $("download-controls").addEventListener("click", () => downloadControls(controls.last.response));
  },
  on: {
    surfaces: (n) => {
      $("controls-actions").hidden = n === 0;
    },
  },
  request: () => (surfaces.rows ? { ...editorRequest("controls", { withVelocity: false }), velocities: airspeeds.read() } : null),
  words: () => ({ busy: "Control effectiveness", failed: "Control effectiveness: failed.", cancelled: "Control effectiveness: cancelled." }),
  render({ request, response }) {
    $("fig-controls").hidden = false;
    drawControls(response);
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
    $("download-json").disabled = false;
    $("download-controls").disabled = false;
    return `Control effectiveness of ${plural(response.reversals.length, "surface")} at ${response.points.length} airspeeds.`;
  },
  results: () => controls.last ?? null,
});
