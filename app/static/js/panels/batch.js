// A batch: independent solves run as one job (POST /jobs, operation batch), each answered or
// its problem given in place. Its solves come from a loaded batch body (kept as given), or are
// this page's wing and flight, added one at a time.

import * as api from "../api.js";
import { $, el, f, plural, signed } from "../dom.js";
import { editorRequest } from "../editor/request.js";
import { drawBatch } from "../figures/batch.js";
import { makeFigure, operationBlock, revealBlock, showBlock } from "../panel-dom.js";
import { showProblem } from "../problems.js";
import { definePanel } from "../registry.js";
import { run } from "../run.js";

let items = [];

function updateCount() {
  $("batch-hint").textContent = items.length
    ? `${plural(items.length, "solve")} in the batch.`
    : "No solves yet: load a batch's JSON, or add this page's wing and flight.";
}

const COLUMNS = [
  ["#", (item) => String(item.index + 1)],
  ["V [m/s]", (item, request) => f(request?.flight?.velocity, 2)],
  ["status", (item) => item.status],
  ["lift [N]", (item) => f(item.result?.totals.lift, 1)],
  ["tip twist [deg]", (item) => signed(item.result?.totals.tip_twist, 2)],
  ["root bending moment [N·m]", (item) => f(item.result?.totals.root_bending_moment, 1)],
  ["problem", (item) => item.problem?.title ?? ""],
];

function renderTable(request, response) {
  const table = $("batch-table");
  table.tHead.replaceChildren(el("tr", {}, ...COLUMNS.map(([label]) => el("th", { scope: "col" }, label))));
  table.tBodies[0].replaceChildren(
    ...response.items.map((item) => {
      const row = el("tr", { data: { status: item.status }, title: item.problem?.detail });
      for (const [, format] of COLUMNS) row.append(el("td", {}, format(item, request.items[item.index])));
      return row;
    }),
  );
}

const batch = definePanel({
  name: "batch",
  operation: "batch",
  job: true,
  unit: "solves",
  figures: ["batch"],
  takes: ["items"],
  init() {
    const { actions } = operationBlock({
      name: "batch",
      operation: "batch",
      summary: "Batch of solves",
      button: "Run the batch",
      hint: "",
      figure: "fig-batch",
      onRun: () => run(batch),
    });
    const add = el("button", { type: "button", id: "batch-add" }, "Add this solve");
    const empty = el("button", { type: "button", id: "batch-empty" }, "Empty the batch");
    add.addEventListener("click", () => {
      items.push(editorRequest("solve", { withVelocity: true }));
      updateCount();
    });
    empty.addEventListener("click", () => {
      items = [];
      updateCount();
    });
    actions.after(el("p", { className: "row-buttons", id: "batch-buttons" }, add, empty));
    updateCount();
    makeFigure({
      id: "batch",
      title: "Batch",
      caption: "Each solve of the batch: its lift, and in the table its airspeed, tip twist and root bending moment, or its problem.",
      empty: 'Run a batch to draw this figure.',
      charts: [{ id: "chart-batch", label: "Lift of each solve of the batch" }],
      table: "The batch's solves",
    });
  },
  mount(schemas) {
    showBlock("batch", Boolean(schemas.BatchRequest));
  },
  takesBody: (body) => Array.isArray(body.items),
  load(body) {
    if (!Array.isArray(body.items)) return undefined;
    items = [...body.items];
    updateCount();
    revealBlock("batch");
    return `Loaded a batch of ${plural(items.length, "solve")} (run it with "Run the batch").`;
  },
  request() {
    if (items.length) return { items: [...items] };
    showProblem(new api.ProblemError(0, { title: "The batch is empty", detail: 'Load a batch\'s JSON, or add this page\'s wing and flight with "Add this solve".' }));
    return null;
  },
  words: (request) => ({ busy: `Running ${plural(request.items.length, "solve")}`, failed: "Batch failed.", cancelled: "Batch cancelled." }),
  render({ request, response }) {
    $("fig-batch").hidden = false;
    drawBatch(response);
    renderTable(request, response);
    const problems = response.items.filter((item) => item.status !== "ok").length;
    $("batch-verdict").textContent = `${plural(response.items.length, "solve")}: ${response.items.length - problems} answered, ${plural(problems, "problem")}.`;
    $("fig-batch").scrollIntoView({ block: "nearest" });
    $("download-json").disabled = false;
    return `Batch of ${plural(response.items.length, "solve")}: ${plural(problems, "problem")}.`;
  },
  results: () => batch.last ?? null,
});
