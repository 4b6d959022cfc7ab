// Flutter: the V-g and V-f diagrams of the wing's modes over the flutter panel's airspeeds
// (POST /jobs, operation flutter); needs the wing's mass (under Wing).

import * as api from "../api.js";
import { downloadText, toCSV } from "../download.js";
import { $, f } from "../dom.js";
import { Airspeeds } from "../editor/airspeeds.js";
import { hasMass } from "../editor/mass.js";
import { editorRequest } from "../editor/request.js";
import { drawFlutter } from "../figures/flutter.js";
import { render, setControl, value } from "../inputs.js";
import { showProblem } from "../problems.js";
import { definePanel } from "../registry.js";
import { run } from "../run.js";

let airspeeds = null;

// options.aerodynamics for flutter alone: empty sends what the options hold (a loaded body's, or
// none: the API's default, the lattice). Offered as the running API's schema lists them.
const AERODYNAMICS = {
  key: "flutter_aerodynamics",
  label: "Aerodynamics",
  kind: "select",
  value: "",
  options: [
    ["", "the options' (the lattice by default)"],
    ["strip", "strip theory (Theodorsen)"],
    ["lattice", "lattice, lagged strip by strip by C(k)"],
    ["unsteady_lattice", "unsteady vortex lattice (3D wake)"],
  ],
  hint: "Which unsteady aerodynamics give the flutter answer; the figure says which did.",
};

/** The answer's aerodynamic model (response.aerodynamic_model) in words. */
export const MODEL_WORDS = {
  strip_theory: "Theodorsen's strip theory",
  quasi_3d_lattice: "the lattice's steady 3D circulation lagged strip by strip by C(k) (quasi-3D)",
  unsteady_lattice: "the unsteady vortex lattice (its 3D wake shed and convected)",
};

const modelOf = (response) => MODEL_WORDS[response.aerodynamic_model] ?? `${response.aerodynamics} aerodynamics`;

/** The flutter request's options: the editor's, with the panel's aerodynamics when chosen. */
function withAerodynamics(request) {
  const chosen = $("f-flutter_aerodynamics").closest(".field").hidden ? "" : value("flutter_aerodynamics");
  if (!chosen) return request;
  return { ...request, options: { ...request.options, aerodynamics: chosen } };
}

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
    render([AERODYNAMICS], $("flutter"), { form: "flutter-form" });
    $("flutter-form").addEventListener("submit", (event) => {
      event.preventDefault();
      run(flutter);
    });
    $("download-flutter").addEventListener("click", () => downloadFlutter(flutter.last.response));
  },
  mount(schemas) {
    const offered = Boolean(schemas.Wing?.properties?.mass && schemas.MassModel && schemas.FlutterRequest);
    for (const id of ["flutter", "flutter-actions"]) $(id).hidden = !offered;
    const models = schemas.SolverOptions?.properties?.aerodynamics?.enum ?? [];
    const select = $("f-flutter_aerodynamics");
    for (const option of [...select.options]) option.hidden = option.value !== "" && !models.includes(option.value);
    select.closest(".field").hidden = models.length === 0;
  },
  /** A wing with its mass (a /flutter body): its airspeeds are flutter's too. */
  load(body) {
    if (body.wing?.mass) airspeeds.load(body.velocities);
    if (body.wing) setControl("flutter_aerodynamics", body.options?.aerodynamics ?? "");
  },
  request() {
    if (hasMass()) return withAerodynamics({ ...editorRequest("flutter", { withVelocity: false }), velocities: airspeeds.read() });
    showProblem(new api.ProblemError(0, { title: "Flutter needs the wing's mass", detail: 'Tick "the wing has a mass model" under Wing and give its mass per length, centre of gravity and inertia.' }));
    $("mass-on").focus();
    return null;
  },
  words: () => ({ busy: "Flutter", failed: "Flutter: failed.", cancelled: "Flutter: cancelled." }),
  render({ response }) {
    $("fig-flutter").hidden = false;
    drawFlutter(response, { model: modelOf(response) });
    $("flutter-status").textContent = flutterWords(response);
    $("fig-flutter").dataset.status = response.status;
    const lost = response.points.filter((p) => p.status !== "solved").map((p) => f(p.velocity, 2));
    $("flutter-note").textContent =
      `Aerodynamics: ${modelOf(response)}, ${response.unsteady === "theodorsen" ? "with the wake's lag" : "quasi-steady (no lag)"}; ` +
      `linearised about ${response.about === "jig" ? "the unloaded jig" : "the static equilibrium at each airspeed"}.` +
      (lost.length ? ` No equilibrium (no roots) at ${lost.join(", ")} m/s.` : "");
    $("fig-flutter").scrollIntoView({ block: "nearest" });
    $("download-json").disabled = false;
    $("download-flutter").disabled = false;
    return `Flutter (${response.aerodynamic_model ?? response.aerodynamics}): ${response.points.length} airspeeds, ${response.modes.length} modes.`;
  },
  results: () => flutter.last ?? null,
});
