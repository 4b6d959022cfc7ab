// Sizing loads: the editor's wing flown through load cases and/or the cases of a flight
// envelope's V-n diagrams (POST /jobs, operation loads). Draws the V-n diagrams with the cases,
// the loads envelope along the span and the potato plot; a table of the cases and CSVs.
// What the fields do not show of a loaded envelope (its V_A, limits) is kept and sent as given;
// an empty field is not sent (the API's default).

import { $, el, f, plural } from "../dom.js";
import { CaseTable, caseSchema, DEFAULT_CASES } from "../editor/cases.js";
import { editorRequest } from "../editor/request.js";
import { drawEnvelope } from "../figures/sizing.js";
import { downloadCases, downloadEnvelope, renderCases } from "../figures/cases.js";
import { clear } from "../figures/chart.js";
import { drawVn } from "../figures/vn.js";
import { resetControl, setControl, value } from "../inputs.js";
import { makeFigure, operationBlock, revealBlock, showBlock } from "../panel-dom.js";
import { definePanel } from "../registry.js";
import { run } from "../run.js";

const CATEGORIES = ["normal", "utility", "aerobatic", "commuter", "cs25"];

// `list`: a text field of numbers ("250, 300"); `optional`: empty is not sent.
const FIELDS = [
  { key: "loads_envelope", label: "Cases of a flight envelope too (its V-n diagrams)", kind: "flag", value: false },
  { key: "env_weights", path: "envelope.weights", label: "Weights", unit: "N, a list", kind: "text", value: "300", list: true },
  { key: "env_altitudes", path: "envelope.altitudes", label: "Altitudes", unit: "m, a list", kind: "text", value: null, placeholder: "0 (sea level)", list: true, optional: true },
  { key: "env_category", path: "envelope.category", label: "Category", kind: "select", value: "normal", options: CATEGORIES.map((c) => [c, c === "cs25" ? "CS-25 (transport)" : `CS-23 ${c}`]) },
  { key: "env_cl_max", path: "envelope.cl_max", label: "C_L max", unit: "-", value: 1.2 },
  { key: "env_cl_min", path: "envelope.cl_min", label: "C_L min", unit: "-", value: -0.6 },
  { key: "env_cruise_speed", path: "envelope.cruise_speed", label: "Cruise speed V_C (EAS)", unit: "m/s", value: 12, placeholder: "the rule's minimum", optional: true },
  { key: "env_dive_speed", path: "envelope.dive_speed", label: "Dive speed V_D (EAS)", unit: "m/s", value: 16, placeholder: "the rule's minimum", optional: true },
  { key: "loads_stations", path: "stations", label: "Correlated stations", unit: "indices", kind: "text", value: null, placeholder: "the root and mid-span", list: true, optional: true },
];
const ENVELOPE_FIELDS = FIELDS.filter((field) => field.path?.startsWith("envelope."));

let cases = null;
let keptEnvelope = {}; // a loaded envelope's keys no field shows

/** "250, 300" as [250, 300] (a word that is no number: null, which the service names). */
function numbers(text) {
  const words = String(text ?? "").split(/[\s,;]+/).filter(Boolean);
  return words.map((w) => (Number.isFinite(Number(w)) ? Number(w) : null));
}

/** The value of `field` for the request, or undefined when it is not sent. */
function given(field) {
  const v = value(field.key);
  if (field.list) return v.trim() === "" ? (field.optional ? undefined : []) : numbers(v);
  return field.optional && v === null ? undefined : v;
}

function envelope() {
  const body = { ...keptEnvelope };
  for (const field of ENVELOPE_FIELDS) {
    const v = given(field);
    if (v !== undefined) body[field.path.split(".")[1]] = v;
  }
  return body;
}

function showEnvelope() {
  for (const field of FIELDS.slice(1)) {
    const wrap = $(`f-${field.key}`).closest(".field");
    if (field.path.startsWith("envelope.")) wrap.hidden = !value("loads_envelope");
  }
}

function verdict(response) {
  const { info, envelope: env, spar } = response;
  const words = [`${plural(info.cases, "case")}, ${info.answered} with loads.`];
  if (env) {
    const critical = (key) => response.cases[env[`max_${key}_case`][0]]?.name;
    words.push(`At the root: largest bending moment ${f(env.max_bending_moment[0], 1)} N·m (${critical("bending_moment")}), largest shear ${f(env.max_shear[0], 1)} N (${critical("shear")}), torque from ${f(env.min_torque[0], 2)} to ${f(env.max_torque[0], 2)} N·m.`);
  } else {
    words.push("No case has loads: no envelope.");
  }
  if (spar) words.push(`Spar: least ultimate margin ${f(spar.least_ultimate_margin, 3)} at station ${spar.least_margin_station}.`);
  return words.join(" ");
}

const loads = definePanel({
  name: "loads",
  operation: "loads",
  job: true,
  unit: "cases",
  figures: ["vn", "envelope"],
  takes: ["cases", "envelope", "stations"],
  init() {
    const { fieldset } = operationBlock({
      name: "loads",
      operation: "loads",
      summary: "Sizing loads: load cases and a flight envelope",
      legend: "Sizing loads (same wing, with its mass for inertia relief)",
      fields: FIELDS,
      button: "Fly the cases",
      hint: "Each case is trimmed at its airspeed; an empty cell is the API's default.",
      figure: "fig-vn",
      onRun: () => run(loads),
    });
    const table = el("table", { id: "cases-table", className: "stations cases" }, el("caption", { className: "visually-hidden" }, "Load cases: name, airspeed, weight, load factor or lift, aileron and roll rate"), el("thead"), el("tbody"));
    const add = el("button", { type: "button", id: "add-case" }, "Add a case");
    const remove = el("button", { type: "button", id: "remove-case" }, "Remove the last case");
    const hint = el("p", { className: "hint", id: "cases-hint" }, "Load cases, each a trimmed flight (a weight times its load factor, or a lift) at its airspeed; an aileron or a roll rate makes it a rolling pull-out. An empty cell is not sent.");
    fieldset.before(hint, el("div", { className: "table-scroll" }, table), el("p", { className: "row-buttons" }, add, remove));
    cases = new CaseTable(table);
    cases.load(DEFAULT_CASES);
    add.addEventListener("click", () => cases.addCase());
    remove.addEventListener("click", () => cases.removeCase());
    $("f-loads_envelope").addEventListener("change", showEnvelope);
    showEnvelope();
    makeFigure({
      id: "vn",
      title: "V-n diagram",
      caption: "Load factor against equivalent airspeed: each V-n diagram of the envelope (a weight at an altitude) with its named points, and every case flown (hover: its name). The table: each case's flight and its answer.",
      empty: 'Run "Fly the cases" to draw this figure.',
      charts: [{ id: "chart-vn", label: "V-n diagrams with the load cases flown", tall: true }],
      table: "The load cases",
    });
    makeFigure({
      id: "envelope",
      title: "Loads envelope",
      caption: "Largest and smallest shear, bending moment and torque along the span over every case with loads (hover: the case that gives it), and each case's bending moment against torque at the correlated stations with their convex hull.",
      empty: 'Run "Fly the cases" to draw this figure.',
      charts: [
        { id: "chart-envelope-shear", label: "Largest and smallest shear along the span" },
        { id: "chart-envelope-moment", label: "Largest and smallest bending moment along the span" },
        { id: "chart-envelope-torque", label: "Largest and smallest torque along the span" },
        { id: "chart-potato", label: "Bending moment against torque of every case at the correlated stations", tall: true },
      ],
    });
    const csv = [
      el("button", { type: "button", id: "download-loads", disabled: true }, "Loads envelope CSV"),
      el("button", { type: "button", id: "download-cases", disabled: true }, "Load cases CSV"),
    ];
    document.querySelector(".downloads").append(...csv);
    csv[0].addEventListener("click", () => downloadEnvelope(loads.last.response));
    csv[1].addEventListener("click", () => downloadCases(loads.last.response));
  },
  mount(schemas) {
    const offered = Boolean(schemas.LoadsRequest);
    showBlock("loads", offered);
    if (offered) cases.setSchema(caseSchema(schemas));
  },
  /** A loads body (its cases, envelope or stations) into the panel; any other leaves it. */
  load(body) {
    if (!loads.takes.some((key) => key in body)) return undefined;
    revealBlock("loads");
    cases.load(body.cases ?? []);
    const env = body.envelope ?? null;
    setControl("loads_envelope", env !== null);
    const shown = new Set(ENVELOPE_FIELDS.map((field) => field.path.split(".")[1]));
    keptEnvelope = Object.fromEntries(Object.entries(env ?? {}).filter(([key]) => !shown.has(key)));
    for (const field of FIELDS.slice(1)) {
      const v = field.path.startsWith("envelope.") ? env?.[field.path.split(".")[1]] : body[field.path];
      if (v != null) setControl(field.key, Array.isArray(v) ? v.join(", ") : v);
      else if (field.optional && env !== null) $(`f-${field.key}`).value = ""; // not given: not sent
      else resetControl(field.key);
    }
    showEnvelope();
    const count = body.cases?.length ?? 0;
    return `Loaded ${plural(count, "load case")}${env ? " and a flight envelope" : ""} (run them with "Fly the cases").`;
  },
  request() {
    const request = editorRequest("loads", { withVelocity: true });
    delete request.flight; // each case has its own
    const list = cases.cases();
    if (list.length || !value("loads_envelope")) request.cases = list;
    if (value("loads_envelope")) request.envelope = envelope();
    const stations = given(FIELDS.at(-1));
    if (stations !== undefined) request.stations = stations;
    return request;
  },
  words: (request) => {
    const what = [request.cases?.length ? plural(request.cases.length, "case") : "", request.envelope ? "an envelope's cases" : ""].filter(Boolean).join(" and ");
    return { busy: `Flying ${what || "no case"}`, failed: "Sizing loads failed.", cancelled: "Sizing loads cancelled." };
  },
  render({ response }) {
    $("fig-vn").hidden = false;
    drawVn(response);
    renderCases(response);
    $("vn-verdict").textContent = verdict(response);
    $("vn-note").textContent = response.vn.length ? `${plural(response.vn.length, "V-n diagram")}.` : "No envelope: the cases given only.";
    const hasEnvelope = Boolean(response.envelope);
    $("fig-envelope").hidden = !hasEnvelope;
    if (hasEnvelope) drawEnvelope(response);
    else clear("envelope");
    $("fig-vn").scrollIntoView({ block: "nearest" });
    $("download-json").disabled = false;
    $("download-loads").disabled = !hasEnvelope;
    $("download-cases").disabled = false;
    return `Sizing loads: ${plural(response.info.cases, "case")}, ${response.info.answered} with loads.`;
  },
  results: () => loads.last ?? null,
});
