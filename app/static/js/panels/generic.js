// Every operation of the running API that no panel of this page runs (a new one,
// the day it arrives): one panel each, made from the OpenAPI document as the page opens. Its
// request is the editor's wing, flight, options and airspeeds (those its body takes) with a
// loaded body's other keys as given (Request JSON); its answer is shown as it comes: a table of its numbers
// and a line chart of any of its arrays (along the span where they have a `y`). So a new
// operation runs on the page without page code; a dedicated panel replaces this one for it.
//
// Imported after every dedicated panel (main.js): it makes panels only for the operations left.

import { $, el, plural } from "../dom.js";
import { editorRequest } from "../editor/request.js";
import { clear } from "../figures/chart.js";
import { drawAnswer, readAnswer } from "../figures/answer.js";
import { makeFigure, operationBlock, revealBlock, showBlock } from "../panel-dom.js";
import { allPanels, definePanel, panelOf } from "../registry.js";
import { run } from "../run.js";
import { flightTakes, jobOperations, requestKeys, summaryOf } from "../schema.js";
import { state } from "../state.js";
import { airspeeds } from "./sweep.js";

function renderNumbers(id, scalars) {
  const table = $(`${id}-table`);
  table.tHead.replaceChildren(el("tr", {}, el("th", { scope: "col" }, "quantity"), el("th", { scope: "col" }, "value")));
  table.tBodies[0].replaceChildren(
    ...scalars.map(({ path, value }) =>
      el("tr", {}, el("th", { scope: "row" }, path), el("td", {}, typeof value === "number" ? String(Number(value.toPrecision(6))) : String(value))),
    ),
  );
}

/** A panel for `operation`, with its block, its figure and the figure's array chooser. */
function genericPanel(operation) {
  const name = `op-${operation}`;
  const summary = summaryOf(operation) ?? `POST /${operation}`;
  let read = { scalars: [], arrays: [] };
  const panel = definePanel({
    name,
    operation,
    job: true,
    unit: "steps",
    figures: [name],
    /** A body without a wing that is this operation's (its keys, and only its). */
    takesBody: (body) => {
      const keys = requestKeys(operation);
      return Object.keys(body).length > 0 && Object.keys(body).every((key) => keys.includes(key));
    },
    load(body) {
      const keys = requestKeys(operation);
      const own = Object.keys(body).filter((key) => !["wing", "flight", "options", "velocities"].includes(key));
      if (own.length && own.every((key) => keys.includes(key)) && allPanels().every((p) => p === panel || !p.takes?.some((k) => own.includes(k)))) {
        revealBlock(name);
      }
    },
    request() {
      const keys = requestKeys(operation);
      const body = editorRequest(operation, { withVelocity: flightTakes(operation, state.flightMode, "velocity") });
      body.velocities = airspeeds.read(); // a body's airspeeds are the sweep's (editor/load.js)
      return Object.fromEntries(Object.entries(body).filter(([key]) => keys.includes(key)));
    },
    words: () => ({ busy: `${operation}: running`, failed: `${operation}: failed.`, cancelled: `${operation}: cancelled.` }),
    render({ response }) {
      $(`fig-${name}`).hidden = false;
      read = readAnswer(response);
      const chooser = $(`${name}-draw`);
      chooser.replaceChildren(...read.arrays.map((a) => new Option(`${a.path} (against ${a.over})`, a.path)));
      chooser.closest(".field").hidden = read.arrays.length < 2;
      drawAnswer(name, `chart-${name}`, read, chooser.value);
      renderNumbers(name, read.scalars);
      $(`${name}-verdict`).textContent = `POST /${operation} answered: ${plural(read.scalars.length, "number")}, ${plural(read.arrays.length, "array")}.`;
      $(`fig-${name}`).scrollIntoView({ block: "nearest" });
      $("download-json").disabled = false;
      return `${operation}: answered.`;
    },
    results: () => panel.last ?? null,
  });
  operationBlock({
    name,
    operation,
    summary: `${summary} (POST /${operation})`,
    button: `Run ${operation}`,
    hint: "The editor's wing, flight and options, with the rest of a loaded body (Request JSON) as given.",
    figure: `fig-${name}`,
    onRun: () => run(panel),
  });
  const figure = makeFigure({
    id: name,
    title: summary,
    caption: `The answer of POST /${operation} as it comes (this page has no figure of its own for it): an array drawn against the span where it has one, and every number in the table.`,
    empty: `Run "${operation}" to draw this figure.`,
    charts: [{ id: `chart-${name}`, label: `An array of the ${operation} answer`, tall: true }],
    table: "The answer's numbers",
  });
  const chooser = el("select", { id: `${name}-draw` });
  chooser.addEventListener("change", () => drawAnswer(name, `chart-${name}`, read, chooser.value));
  figure.querySelector(".charts").before(el("div", { className: "field", hidden: true }, el("label", { for: `${name}-draw` }, "Draw"), chooser));
  clear(name);
  return panel;
}

definePanel({
  name: "generic",
  /** Panels for the operations no panel runs: made once the running API's document is read. */
  mount() {
    for (const operation of jobOperations()) {
      if (!panelOf(operation)) showBlock(genericPanel(operation).name, true);
    }
  },
});
