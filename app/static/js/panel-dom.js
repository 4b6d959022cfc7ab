// The elements a panel builds for itself (the study's panels are written in index.html): its
// fields and run button in the editor (#operations, under the flight's), and its figure among
// the results (before Figure 14.5, which stays last). A new panel needs no edit of the page.

import { $, el } from "./dom.js";
import { render } from "./inputs.js";

/**
 * The editor block of panel `name`: a fieldset #<name> of `fields` (inputs.js descriptors) in a
 * form of its own (#<name>-form: Enter in a field runs it), then #<name>-actions with its run
 * button #<name>-button (data-operation) and a hint; hidden until the panel shows them. Given a
 * `summary`, the block is a closed <details> #<name>-details with that summary (revealBlock
 * opens it). `onRun()` runs on the button or Enter.
 */
export function operationBlock({ name, operation, legend, summary, fields = [], button, hint, figure, onRun }) {
  const formId = `${name}-form`;
  const form = el("form", { id: formId, novalidate: true });
  form.addEventListener("submit", (event) => {
    event.preventDefault();
    onRun();
  });
  $("flutter-form").after(form);
  const fieldset = el("fieldset", { id: name, className: "grid", hidden: true }, el("legend", {}, legend));
  render(fields, fieldset, { form: formId });
  const actions = el(
    "div",
    { id: `${name}-actions`, className: "actions", hidden: true },
    el("button", { type: "submit", id: `${name}-button`, className: "primary", form: formId, data: { operation } }, button),
    el("span", { className: "hint", id: `${name}-hint` }, hint),
    figure ? el("a", { className: "to-results", href: `#${figure}` }, "Results") : null,
  );
  const parts = [...(fields.length ? [fieldset] : []), actions];
  if (summary) {
    for (const part of parts) part.hidden = false; // the details is what shows and hides
    const details = el("details", { id: `${name}-details`, className: "operation", hidden: true }, el("summary", {}, summary), ...parts);
    $("operations").append(details);
  } else {
    $("operations").append(...parts);
  }
  return { fieldset, actions, form };
}

/** Show or hide panel `name`'s editor block. */
export function showBlock(name, shown) {
  const details = $(`${name}-details`);
  for (const element of details ? [details] : [$(name), $(`${name}-actions`)]) {
    if (element) element.hidden = !shown;
  }
}

/** Open panel `name`'s block (a loaded body is for it). */
export function revealBlock(name) {
  const details = $(`${name}-details`);
  if (details) details.open = true;
}

/**
 * The figure #fig-<id> (state "empty" until drawn, hidden until the panel shows it): its
 * caption (`title`, `caption` and a #<id>-note), what it says while empty, a #<id>-verdict line,
 * its `charts` ([{id, label, tall}]: one canvas each), an optional table #<id>-table, and its PNG
 * export button.
 */
export function makeFigure({ id, title, caption, empty, charts, table }) {
  const figureId = `fig-${id}`;
  const figure = el(
    "figure",
    { id: figureId, className: "figure", data: { state: "empty", title }, hidden: true },
    el("figcaption", {}, el("strong", {}, `${title}.`), ` ${caption} `, el("span", { id: `${id}-note` })),
    el("p", { className: "empty" }, empty),
    el("p", { id: `${id}-verdict`, className: "verdict", role: "status" }),
    el(
      "div",
      { className: "charts" },
      ...charts.map((chart) =>
        el("div", { className: chart.tall ? "chart tall" : "chart" }, el("canvas", { id: chart.id, role: "img", "aria-label": chart.label })),
      ),
    ),
    table
      ? el(
          "div",
          { className: "table-scroll" },
          el("table", { id: `${id}-table`, className: "sweep-table" }, el("caption", {}, table), el("thead"), el("tbody")),
        )
      : null,
    el("p", { className: "export" }, el("button", { type: "button", className: "export-png", data: { figure: figureId } }, `${title} as PNG`)),
  );
  $("fig-14-5").before(figure);
  return figure;
}
