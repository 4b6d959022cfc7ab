// Gust loads: the editor's wing (with its mass) and flight (with the aircraft's weight) in the
// 1-cos gusts of CS-25.341(a) over the gust gradients H (the tuned gust) and in continuous
// turbulence (POST /jobs, operation gust). Its fields are the API's GustSettings, read from the
// OpenAPI document (names, units, limits, defaults); an empty field is not sent (the API's
// default), so a pasted body is sent as given. Draws the time histories of any gradient's gust
// (the tuned one first), the envelopes of total loads along the span (1 g plus the 1-cos gusts,
// and turbulence's design loads), and the tuned-gust search against Pratt's load factor.

import { $, el, f, plural } from "../dom.js";
import { editorRequest } from "../editor/request.js";
import { downloadGustEnvelope, downloadGusts, downloadHistories, drawGustEnvelope, drawHistories, drawTuning, gustNumbers } from "../figures/gust.js";
import { applyLimits, render, setControl, value } from "../inputs.js";
import { makeFigure, operationBlock, revealBlock, showBlock } from "../panel-dom.js";
import { definePanel } from "../registry.js";
import { run } from "../run.js";
import { flightTakes, resolve } from "../schema.js";
import { state } from "../state.js";

let fields = []; // the descriptors made from GustSettings: {key, name, kind, list, property}
let keptGust = {}; // a loaded gust's keys no field shows
let hadGust = false; // the loaded body had a `gust` (maybe {}): sent even with no field filled
let fieldset = null;

/** A GustSettings property's members: its number/array/boolean/string schema (null left out). */
const members = (property) => [property, ...(property.anyOf ?? []), ...(property.oneOf ?? [])].map(resolve).filter((p) => p && p.type && p.type !== "null");

/** "[m] Longest gust gradient ..." as {unit: "m", text: "Longest gust gradient ..."}. */
function described(property) {
  const match = /^\[([^\]]*)\]\s*(.*)$/s.exec(property.description ?? "");
  return match ? { unit: match[1], text: match[2] } : { unit: "", text: property.description ?? "" };
}

/** An input descriptor (inputs.js) for the GustSettings property `name`. */
function descriptor(name, property) {
  const kinds = members(property);
  const type = kinds[0]?.type ?? "number";
  const { unit, text } = described(property);
  const base = { key: `gust_${name}`, name, label: property.title ?? name, unit: unit && unit !== "-" ? unit : undefined, value: null, hint: text.replace(/: from -?[\d.e+-]+ to .*$/s, ""), property };
  const api = property.default;
  const defaultWord = api === undefined || api === null ? "none" : String(api);
  if (type === "boolean") return { ...base, kind: "select", options: [["", `API default (${defaultWord})`], ["true", "yes"], ["false", "no"]], bool: true };
  if (kinds[0]?.enum) return { ...base, kind: "select", options: [["", `API default (${defaultWord})`], ...kinds[0].enum.map((v) => [v, v])] };
  if (type === "array") return { ...base, kind: "text", list: true, unit: `${unit || "-"}, a list`, placeholder: "none" };
  return { ...base, kind: type === "integer" ? "integer" : "number", placeholder: `default ${defaultWord}` };
}

/** "9, 52, 107" as [9, 52, 107] (a word that is no number: null, which the service names). */
function numbers(text) {
  const words = String(text ?? "").split(/[\s,;]+/).filter(Boolean);
  return words.map((w) => (Number.isFinite(Number(w)) ? Number(w) : null));
}

/** The value of `field` for the request, or undefined when empty (not sent). */
function given(field) {
  const v = value(field.key);
  if (field.list) return v.trim() === "" ? undefined : numbers(v);
  if (field.kind === "select") return v === "" ? undefined : field.bool ? v === "true" : v;
  return v === null && $(`f-${field.key}`).value.trim() === "" ? undefined : v;
}

/** The request's `gust`, or undefined when nothing is given. */
function gustSettings() {
  const body = { ...keptGust };
  for (const field of fields) {
    const v = given(field);
    if (v !== undefined) body[field.name] = v;
  }
  return Object.keys(body).length || hadGust ? body : undefined;
}

/** Show a loaded body's gust (null: none, every field empty). */
function fillFields(gust) {
  const shown = new Set(fields.map((field) => field.name));
  keptGust = Object.fromEntries(Object.entries(gust ?? {}).filter(([key]) => !shown.has(key)));
  for (const field of fields) {
    const v = gust?.[field.name];
    if (v === undefined || v === null) $(`f-${field.key}`).value = "";
    else setControl(field.key, Array.isArray(v) ? v.join(", ") : String(v));
  }
}

function verdict(response) {
  const tn = response.gusts[response.tuned_load_factor];
  const words = [
    `${plural(response.gusts.length, "gust gradient")}: the tuned gust H = ${f(tn.gradient, 1)} m (U_ds ${f(tn.gust_velocity, 2)} m/s TAS) gives n = ${f(tn.max_load_factor, 3)}; Pratt's K_g = ${f(response.pratt_alleviation, 3)} (mass ratio ${f(response.mass_ratio, 2)}) gives n = ${f(response.pratt_load_factor, 3)}.`,
    `Root bending moment, total: ${f(response.envelope.max_bending_moment[0], 1)} N·m (1-cos)${response.turbulence ? `, ${f(response.turbulence.max_bending_moment[0], 1)} N·m (turbulence)` : ""}.`,
  ];
  if (response.findings?.length) words.push(response.findings.join(" "));
  return words.join(" ");
}

function renderNumbers(response) {
  const table = $("gust-tuned-table");
  table.tHead.replaceChildren(el("tr", {}, el("th", { scope: "col" }, "quantity"), el("th", { scope: "col" }, "value"), el("th", { scope: "col" }, "unit")));
  table.tBodies[0].replaceChildren(
    ...gustNumbers(response).map(([label, v, unit]) => el("tr", {}, el("th", { scope: "row" }, label), el("td", {}, String(Number(v.toPrecision(5)))), el("td", {}, unit))),
  );
}

/** The gust chooser: every gradient (the tuned one first chosen) and a given profile. */
function fillChooser(response) {
  const chooser = $("gust-case");
  const options = response.gusts.map((c, i) => new Option(`${c.name}${i === response.tuned_load_factor ? " (tuned)" : ""}`, String(i)));
  if (response.profile) options.push(new Option(`${response.profile.name} (the given profile)`, "profile"));
  chooser.replaceChildren(...options);
  chooser.value = String(response.tuned_load_factor);
}

const gust = definePanel({
  name: "gust",
  operation: "gust",
  job: true,
  unit: "steps",
  figures: ["gust-time", "gust-envelope", "gust-tuned"],
  takes: ["gust"],
  init() {
    const block = operationBlock({
      name: "gust",
      operation: "gust",
      summary: "Gust loads: 1-cos gusts (the tuned gust) and continuous turbulence",
      button: "Fly the gusts",
      hint: "The editor's wing (with its mass) and flight (with the aircraft's weight); an empty field is the API's default.",
      figure: "fig-gust-time",
      onRun: () => run(gust),
    });
    fieldset = el("fieldset", { id: "gust-fields", className: "grid" }, el("legend", {}, "Gusts (CS-25.341)"));
    block.actions.before(fieldset);
    makeFigure({
      id: "gust-time",
      title: "Gust response in time",
      caption: "A 1-cos up gust's load factor (with Pratt's for comparison) and the elastic tip's incremental deflection and twist against time; the tuned gust (largest load factor) first, any other gradient from the list.",
      empty: 'Run "Fly the gusts" to draw this figure.',
      charts: [
        { id: "chart-gust-n", label: "Load factor against time in the chosen gust" },
        { id: "chart-gust-tip", label: "Tip deflection and twist against time in the chosen gust" },
      ],
    });
    const chooser = el("select", { id: "gust-case" });
    chooser.addEventListener("change", () => drawHistories(gust.last.response, chooser.value));
    $("fig-gust-time").querySelector(".charts").before(el("div", { className: "field" }, el("label", { for: "gust-case" }, "Gust"), chooser));
    makeFigure({
      id: "gust-envelope",
      title: "Gust loads envelope",
      caption: "Total shear, bending moment and torque along the span: the 1 g loads, plus and minus the largest incremental load of any 1-cos gradient (up and down), and continuous turbulence's design loads P_1g ± U_sigma A-bar.",
      empty: 'Run "Fly the gusts" to draw this figure.',
      charts: [
        { id: "chart-gust-shear", label: "Total shear along the span in gusts and turbulence" },
        { id: "chart-gust-moment", label: "Total bending moment along the span in gusts and turbulence" },
        { id: "chart-gust-torque", label: "Total torque along the span in gusts and turbulence" },
      ],
    });
    makeFigure({
      id: "gust-tuned",
      title: "Tuned gust",
      caption: "Each 1-cos gust's peak load factor and peak incremental root bending moment against its gradient H, the tuned gust marked, and Pratt's load factor (K_g, CS-23.341) as a reference. The table: the answer's numbers.",
      empty: 'Run "Fly the gusts" to draw this figure.',
      charts: [
        { id: "chart-gust-tuned-n", label: "Peak load factor against the gust gradient" },
        { id: "chart-gust-tuned-moment", label: "Peak root bending moment against the gust gradient" },
      ],
      table: "Gust loads: the numbers",
    });
    const csv = [
      el("button", { type: "button", id: "download-gust-envelope", disabled: true }, "Gust envelope CSV"),
      el("button", { type: "button", id: "download-gusts", disabled: true }, "Gust gradients CSV"),
      el("button", { type: "button", id: "download-gust-histories", disabled: true }, "Gust time histories CSV"),
    ];
    document.querySelector(".downloads").append(...csv);
    csv[0].addEventListener("click", () => downloadGustEnvelope(gust.last.response));
    csv[1].addEventListener("click", () => downloadGusts(gust.last.response));
    csv[2].addEventListener("click", () => downloadHistories(gust.last.response, $("gust-case").value));
  },
  mount(schemas) {
    const settings = schemas.GustSettings;
    showBlock("gust", Boolean(settings));
    if (!settings) return;
    fieldset.querySelectorAll(".field").forEach((node) => node.remove());
    fields = Object.entries(settings.properties ?? {}).map(([name, property]) => descriptor(name, property));
    render(fields, fieldset, { form: "gust-form" });
    for (const field of fields) {
      const number = members(field.property).find((p) => p.type === "number" || p.type === "integer");
      if (number) applyLimits($(`f-${field.key}`), number);
    }
  },
  /** A body's gust into the fields; a body with a wing and no gust empties them (defaults). */
  load(body) {
    if (!("gust" in body) && !("wing" in body)) return undefined;
    hadGust = "gust" in body && body.gust !== null;
    fillFields(body.gust);
    if (!("gust" in body)) return undefined;
    revealBlock("gust");
    return 'Loaded gust settings (run them with "Fly the gusts").';
  },
  request() {
    const request = editorRequest("gust", { withVelocity: flightTakes("gust", state.flightMode, "velocity") });
    const settings = gustSettings();
    if (settings !== undefined) request.gust = settings;
    return request;
  },
  words: () => ({ busy: "Flying the gusts", failed: "Gust loads failed.", cancelled: "Gust loads cancelled." }),
  render({ response }) {
    for (const id of gust.figures) $(`fig-${id}`).hidden = false;
    fillChooser(response);
    drawHistories(response, $("gust-case").value);
    drawGustEnvelope(response);
    drawTuning(response);
    renderNumbers(response);
    $("gust-time-verdict").textContent = verdict(response);
    $("gust-envelope-note").textContent = response.turbulence ? "" : "No turbulence asked: the 1-cos gusts only.";
    $("fig-gust-time").scrollIntoView({ block: "nearest" });
    $("download-json").disabled = false;
    for (const id of ["download-gust-envelope", "download-gusts", "download-gust-histories"]) $(id).disabled = false;
    const tn = response.gusts[response.tuned_load_factor];
    return `Gust loads: ${plural(response.gusts.length, "gradient")}, tuned H = ${f(tn.gradient, 1)} m, n = ${f(tn.max_load_factor, 3)}.`;
  },
  results: () => gust.last ?? null,
});
