// Flutter: the V-g and V-f diagrams of the wing's modes over the flutter panel's airspeeds
// (POST /jobs, operation flutter); needs the wing's mass (under Wing).

import * as api from "../api.js";
import { downloadText, toCSV } from "../download.js";
import { $, f } from "../dom.js";
import { Airspeeds } from "../editor/airspeeds.js";
import { hasMass } from "../editor/mass.js";
import { editorRequest } from "../editor/request.js";
import { drawFlutter } from "../figures/flutter.js";
import { showProblem } from "../problems.js";
import { definePanel } from "../registry.js";
import { run } from "../run.js";

let airspeeds = null;

function flutterWords(response) {
  const { flutter: onset, no_flutter: none, divergence } = response;
  const words = [];
  if (response.status === "flutter") {
    words.push(
      `Flutter at ${f(onset.velocity, 2)} m/s: mode ${onset.mode + 1}'s damping crosses zero there, at ${f(onset.frequency, 1)} rad/s ` +
        `(${f(onset.frequency / (2 * Math.PI), 2)} Hz, reduced frequency ${f(onset.reduced_frequency, 3)}).`,
    );
  } else if (response.status === "no_flutter_in_range") {
    words.push(
      `No flutter between ${f(none.searched_from, 2)} and ${f(none.searched_to, 2)} m/s: every mode stays damped; the least damping, ` +
        `${none.least_damping.toPrecision(3)}, is mode ${none.least_damped_mode + 1}'s at ${f(none.least_damped_velocity, 2)} m/s.`,
    );
  } else {
    words.push("No airspeed has a static equilibrium to linearise about: no flutter analysis was possible (each point says why).");
  }
  if (divergence) {
    words.push(`Divergence (${divergence.kind.replaceAll("_", " ")}) at ${f(divergence.velocity, 2)} m/s${divergence.within_range ? "" : ", beyond the airspeeds analysed"}.`);
    if (onset) words.push(onset.velocity < divergence.velocity ? "Flutter comes first." : "Divergence comes first.");
  } else {
    words.push("No divergence.");
  }
  return words.join(" ");
}

/** The V-g and V-f data: per airspeed, each mode's damping ratio and frequency. */
function downloadFlutter(response) {
  const { points, modes } = response;
  const columns = [
    ["velocity [m/s]", points.map((p) => p.velocity)],
    ["status", points.map((p) => p.status)],
    ["dynamic_pressure [Pa]", points.map((p) => p.dynamic_pressure)],
  ];
  modes.forEach((_, m) => {
    columns.push(
      [`mode ${m + 1} damping [-]`, points.map((p) => p.damping?.[m] ?? null)],
      [`mode ${m + 1} frequency [rad/s]`, points.map((p) => p.frequency?.[m] ?? null)],
    );
  });
  columns.push(["divergence_rate [1/s]", points.map((p) => p.divergence_rate ?? null)], ["reason", points.map((p) => p.reason ?? null)]);
  downloadText("flexwing-flutter.csv", "text/csv", toCSV(columns));
}

const flutter = definePanel({
  name: "flutter",
  operation: "flutter",
  job: true,
  figures: ["flutter"],
  init() {
    airspeeds = new Airspeeds("flutter", $("flutter"), { start: 2, stop: 21, count: 20 }, { form: "flutter-form" });
    $("flutter-form").addEventListener("submit", (event) => {
      event.preventDefault();
      run(flutter);
    });
    $("download-flutter").addEventListener("click", () => downloadFlutter(flutter.last.response));
  },
  mount(schemas) {
    const offered = Boolean(schemas.Wing?.properties?.mass && schemas.MassModel && schemas.FlutterRequest);
    for (const id of ["flutter", "flutter-actions"]) $(id).hidden = !offered;
  },
  /** A wing with its mass (a /flutter body): its airspeeds are flutter's too. */
  load(body) {
    if (body.wing?.mass) airspeeds.load(body.velocities);
  },
  request() {
    if (hasMass()) return { ...editorRequest("flutter", { withVelocity: false }), velocities: airspeeds.read() };
    showProblem(new api.ProblemError(0, { title: "Flutter needs the wing's mass", detail: 'Tick "the wing has a mass model" under Wing and give its mass per length, centre of gravity and inertia.' }));
    $("mass-on").focus();
    return null;
  },
  words: () => ({ busy: "Flutter", failed: "Flutter: failed.", cancelled: "Flutter: cancelled." }),
  render({ response }) {
    $("fig-flutter").hidden = false;
    drawFlutter(response);
    $("flutter-status").textContent = flutterWords(response);
    $("fig-flutter").dataset.status = response.status;
    const lost = response.points.filter((p) => p.status !== "solved").map((p) => f(p.velocity, 2));
    $("flutter-note").textContent =
      `Linearised about ${response.about === "jig" ? "the unloaded jig" : "the static equilibrium at each airspeed"}; ${response.aerodynamics} aerodynamics, ` +
      `${response.unsteady === "theodorsen" ? "Theodorsen's lag" : "quasi-steady"}.` +
      (lost.length ? ` No equilibrium (no roots) at ${lost.join(", ")} m/s.` : "");
    $("fig-flutter").scrollIntoView({ block: "nearest" });
    $("download-json").disabled = false;
    $("download-flutter").disabled = false;
    return `Flutter: ${response.points.length} airspeeds, ${response.modes.length} modes.`;
  },
  results: () => flutter.last ?? null,
});
