// The page: the wing and flight editor (editor/), one panel per operation of the API and per
// figure (panels/), each registering itself (registry.js), and the figures they draw
// (figures/). Plain ES modules, no build step; every asset comes from this app (see
// app/routes/page.py). A new panel is one module in panels/ and one import line below.

import { initFlight, mountFlight } from "./editor/flight.js";
import { initLoad } from "./editor/load.js";
import { updateSurfaces } from "./editor/surfaces.js";
import { initWing, mountWing } from "./editor/wing.js";
import { clear, registry } from "./figures/chart.js";
import { installKeyBox } from "./key.js";
import { allPanels, describe, panelOf } from "./registry.js";
import { run } from "./run.js";
import { readDocument, schemas } from "./schema.js";
import { state } from "./state.js";
import { wireCancel } from "./status.js";

// The panels, in the page's order: one line each.
import "./panels/solve.js";
import "./panels/sweep.js";
import "./panels/controls.js";
import "./panels/flutter.js";
import "./panels/roll.js";
import "./panels/optimize.js";
import "./panels/batch.js";
import "./panels/loads.js";
import "./panels/gust.js";
import "./panels/generic.js"; // after every panel: the operations left to it
import "./panels/shape.js";
import "./panels/downloads.js";

// What tests (and curious users) can read: window.__flexwing.figures["14.2"].series, the runs in
// .state.runs, each operation's figures in .operations (a generic panel's too, once mounted).
window.__flexwing = {
  figures: registry,
  state,
  get operations() {
    return describe(); // the generic panels are made once the API's document is read
  },
  ready: false,
  get totals() {
    return panelOf("solve")?.last?.response.totals ?? null;
  },
};

/** The study's wing, solved and swept: as the page opens, and again once a key is given. */
async function opening() {
  await run(panelOf("solve"));
  await run(panelOf("sweep"));
}

async function main() {
  initFlight();
  initWing();
  initLoad();
  wireCancel();
  for (const panel of allPanels()) {
    panel.init?.();
    for (const id of panel.figures ?? []) clear(id);
  }
  installKeyBox(opening);
  await readDocument();
  mountFlight(schemas());
  mountWing(schemas());
  for (const panel of allPanels()) panel.mount?.(schemas());
  updateSurfaces();
  await opening();
  window.__flexwing.ready = true;
  document.body.dataset.ready = "true";
}

main();
