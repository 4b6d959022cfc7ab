// Roll: the wing's antisymmetric response to its ailerons at the flight panel's condition, at a
// given roll rate or in a free roll (POST /jobs, operation roll); offered while the wing has
// control surfaces.

import { $, f, signed } from "../dom.js";
import { editorRequest } from "../editor/request.js";
import { surfaces } from "../editor/surfaces.js";
import { drawRoll } from "../figures/roll.js";
import { resetControl, value } from "../inputs.js";
import { makeFigure, operationBlock, showBlock } from "../panel-dom.js";
import { definePanel } from "../registry.js";
import { run } from "../run.js";

const FIELDS = [
  { key: "roll_rate", path: "roll_rate", label: "Roll rate p", unit: "rad/s", value: 0 },
  { key: "free_roll", path: "free_roll", label: "Free roll (solve for p)", kind: "flag", value: false },
  {
    key: "roll_method",
    path: "method",
    label: "Method",
    kind: "select",
    value: "auto",
    options: [
      ["auto", "auto: exact where it applies"],
      ["antisymmetric", "antisymmetric (exact)"],
      ["linearised", "linearised"],
    ],
  },
];

let offered = false;
let surfaceCount = 0;

const show = () => showBlock("roll", offered && surfaceCount > 0);

function freeRoll() {
  $("f-roll_rate").disabled = value("free_roll");
}

function verdict(response) {
  const { rolling_moment: moment, rigid_rolling_moment: rigid } = response;
  const share = rigid ? ` (${f((100 * moment) / rigid, 0)} % of the rigid wing's ${f(rigid, 2)} N·m)` : "";
  const rate = response.free_roll
    ? `Free roll at p = ${f(response.roll_rate, 4)} rad/s: pb/2V = ${f(response.helix_angle, 4)}, the rolling moment vanishes (the rigid wing's at that rate: ${f(rigid, 2)} N·m).`
    : `Rolling moment ${f(moment, 2)} N·m${share} at p = ${f(response.roll_rate, 3)} rad/s (pb/2V = ${f(response.helix_angle, 4)}); coefficient ${signed(response.rolling_moment_coefficient, 5)}.`;
  const { stable, margin, antisymmetric_divergence_velocity: divergence } = response.stability;
  const stability = `Antisymmetric margin ${f(margin, 3)} (${stable ? "stable" : "UNSTABLE"}${divergence != null ? `; antisymmetric divergence at ${f(divergence, 2)} m/s` : ""}).`;
  return `${rate} ${stability}`;
}

const roll = definePanel({
  name: "roll",
  operation: "roll",
  job: true,
  figures: ["roll"],
  takes: ["roll_rate", "free_roll", "method"],
  init() {
    operationBlock({
      name: "roll",
      operation: "roll",
      legend: "Roll: the ailerons' antisymmetric response (same wing and flight as a solve)",
      fields: FIELDS,
      button: "Roll",
      hint: "Rolling moment and both wings' loads; enter in a roll field runs it.",
      figure: "fig-roll",
      onRun: () => run(roll),
    });
    $("f-free_roll").addEventListener("change", freeRoll);
    makeFigure({
      id: "roll",
      title: "Roll",
      caption: "Both wings' lift per unit span (flexible and rigid) and twist across the span, the left wing at negative y.",
      empty: "Add an aileron and run \"Roll\" to draw this figure.",
      charts: [
        { id: "chart-roll-lift", label: "Lift per unit span across both wings, flexible and rigid", tall: true },
        { id: "chart-roll-twist", label: "Twist across both wings" },
      ],
    });
  },
  mount(schemas) {
    offered = Boolean(schemas.RollRequest);
    show();
  },
  on: {
    surfaces: (n) => {
      surfaceCount = n;
      show();
    },
  },
  load(body) {
    resetControl("roll_rate", body.roll_rate);
    resetControl("free_roll", body.free_roll);
    resetControl("roll_method", body.method);
    freeRoll();
  },
  request() {
    if (!surfaces.rows) return null;
    const request = { ...editorRequest("roll", { withVelocity: true }), free_roll: value("free_roll"), method: value("roll_method") };
    if (!request.free_roll) request.roll_rate = value("roll_rate");
    return request;
  },
  words: (request) => ({ busy: `Rolling at ${request.flight.velocity} m/s`, failed: "Roll failed.", cancelled: "Roll cancelled." }),
  render({ response }) {
    $("fig-roll").hidden = false;
    drawRoll(response);
    $("roll-verdict").textContent = verdict(response);
    const hinges = response.hinge_moments.map((h) => `${h.name} ${f(h.right, 2)} (right), ${f(h.left, 2)} (left)`);
    $("roll-note").textContent =
      `${response.method === "antisymmetric" ? "The exact antisymmetric equilibrium" : "Linearised about the symmetric equilibrium"}; lift ${f(response.lift, 1)} N.` +
      (hinges.length ? ` Hinge moments [N·m]: ${hinges.join("; ")}.` : "");
    $("fig-roll").scrollIntoView({ block: "nearest" });
    $("download-json").disabled = false;
    return response.free_roll
      ? `Free roll at ${f(response.roll_rate, 4)} rad/s.`
      : `Rolling moment ${f(response.rolling_moment, 2)} N·m.`;
  },
  results: () => roll.last ?? null,
});
