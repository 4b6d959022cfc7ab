// Optimise: the jig twist (and, given a spar and its design, the spar's wall) of the wing that
// carries the flight panel's weight or lift at its airspeed with the least induced drag or spar
// mass (POST /jobs, operation optimize). What the fields do not show of a loaded design (the
// wall's bounds) is kept and sent as given; its constraints too (editor/load.js).

import * as api from "../api.js";
import { $, f, plural } from "../dom.js";
import { editorRequest } from "../editor/request.js";
import { drawOptimum } from "../figures/optimize.js";
import { resetControl, value } from "../inputs.js";
import { makeFigure, operationBlock, revealBlock, showBlock } from "../panel-dom.js";
import { showProblem } from "../problems.js";
import { definePanel } from "../registry.js";
import { run } from "../run.js";
import { state } from "../state.js";

const FIELDS = [
  {
    key: "objective",
    path: "objective",
    label: "Minimise",
    kind: "select",
    value: "induced_drag",
    options: [
      ["induced_drag", "induced drag (near field)"],
      ["trefftz_drag", "induced drag (Trefftz plane)"],
      ["spar_mass", "spar mass"],
    ],
  },
  { key: "control_points", path: "design.jig_twist.control_points", label: "Twist control points", unit: "-", kind: "integer", value: 6, placeholder: "every station" },
  { key: "twist_lower", path: "design.jig_twist.lower", label: "Lowest jig twist", unit: "deg", value: -15 },
  { key: "twist_upper", path: "design.jig_twist.upper", label: "Highest jig twist", unit: "deg", value: 15 },
  { key: "smoothness_weight", path: "smoothness_weight", label: "Smoothness weight", unit: "N/deg^2", value: 0 },
];

let design = {}; // the loaded design, kept where the fields do not show it

function verdict(optimum) {
  const e = optimum.span_efficiency;
  const words = [`Induced drag ${f(optimum.induced_drag, 4)} N at span efficiency ${f(e, 4)} (Trefftz plane: ${f(optimum.trefftz_drag, 4)} N).`];
  if (optimum.rigid) {
    const change = (100 * (optimum.induced_drag - optimum.rigid.induced_drag)) / optimum.rigid.induced_drag;
    words.push(`The rigid wing's optimum: ${f(optimum.rigid.induced_drag, 4)} N (${change >= 0 ? "+" : ""}${f(change, 2)} % for the flexible wing).`);
  }
  if (optimum.spar_mass != null) words.push(`Spar mass ${f(optimum.spar_mass, 3)} kg.`);
  return words.join(" ");
}

const optimize = definePanel({
  name: "optimize",
  operation: "optimize",
  job: true,
  figures: ["optimize"],
  takes: ["objective", "design", "smoothness_weight"],
  init() {
    operationBlock({
      name: "optimize",
      operation: "optimize",
      summary: "Optimise the jig twist",
      legend: "Design (same wing, trimmed to the weight or lift above at the airspeed above)",
      fields: FIELDS,
      button: "Optimise",
      hint: "Control points empty: every station a variable. Enter in a field runs it.",
      figure: "fig-optimize",
      onRun: () => run(optimize),
    });
    makeFigure({
      id: "optimize",
      title: "Optimal jig twist",
      caption: "The optimal jig twist of the flexible wing and of the rigid one, and the optimal wing's lift per unit span against the elliptic loading of the same lift.",
      empty: 'Fly at a weight or a lift and run "Optimise" to draw this figure.',
      charts: [
        { id: "chart-optimize-twist", label: "Optimal jig twist along the span, flexible and rigid" },
        { id: "chart-optimize-lift", label: "Lift per unit span of the optimal wing and the elliptic loading" },
      ],
    });
  },
  mount(schemas) {
    showBlock("optimize", Boolean(schemas.OptimizeRequest));
  },
  load(body) {
    if (optimize.takes.some((key) => key in body)) revealBlock("optimize");
    design = body.design ?? {};
    const twist = design.jig_twist ?? {};
    resetControl("objective", body.objective);
    // A null control_points is every station (an empty field); absent, the API's default.
    if (twist.control_points === null) $("f-control_points").value = "";
    else resetControl("control_points", twist.control_points);
    resetControl("twist_lower", twist.lower);
    resetControl("twist_upper", twist.upper);
    resetControl("smoothness_weight", body.smoothness_weight);
  },
  request() {
    if (state.flightMode === "alpha") {
      showProblem(new api.ProblemError(0, { title: "An optimum needs a lift to carry", detail: 'Choose "weight (trimmed)" or "lift" under "Fly at": the design carries it at the airspeed given.' }));
      $("flight-mode-weight").focus();
      return null;
    }
    const jigTwist = { ...design.jig_twist, control_points: value("control_points"), lower: value("twist_lower"), upper: value("twist_upper") };
    return {
      ...editorRequest("optimize", { withVelocity: true }),
      objective: value("objective"),
      design: { ...design, jig_twist: jigTwist },
      smoothness_weight: value("smoothness_weight"),
    };
  },
  words: (request) => ({ busy: `Optimising at ${request.flight.velocity} m/s`, failed: "Optimisation failed.", cancelled: "Optimisation cancelled." }),
  render({ response }) {
    $("fig-optimize").hidden = false;
    drawOptimum(response);
    $("optimize-verdict").textContent = verdict(response);
    const active = response.constraints.filter((c) => c.active).map((c) => c.name);
    $("optimize-note").textContent =
      `Minimised: ${response.objective.replaceAll("_", " ")}, ${f(response.objective_value, 5)}` +
      (response.control_points ? `; ${plural(response.control_points.length, "control point")}` : "; every station a variable") +
      (active.length ? `; active constraints: ${active.join(", ")}.` : "; no constraint active.");
    $("fig-optimize").scrollIntoView({ block: "nearest" });
    $("download-json").disabled = false;
    return `Optimised: ${f(response.objective_value, 5)} (${response.objective.replaceAll("_", " ")}).`;
  },
  results: () => optimize.last ?? null,
});
