// The page's panels: each is one module (panels/*.js) that calls definePanel once, and one
// import line in main.js. A panel that runs an operation of the API names it; the registry
// counts its runs, disables its buttons while another runs (button[data-operation]), clears its
// figures as the page opens, gives every panel each loaded body, and hands it the running API's
// schemas. A new panel touches no other module.
//
// A panel is an object with (every member optional but `name`):
//   name        a unique name ("roll")
//   operation   the POST /jobs operation it runs ("roll"); its run button has data-operation
//   job         true: run as a job (progress, Cancel), false: POST /<operation> and wait
//   figures     the ids of the figures it draws (figures/chart.js), cleared as the page opens
//   takes       the top-level keys of a request body it shows in its own fields
//   init()                build its fields and figure, wire its buttons (before the API is read)
//   mount(schemas)        show itself if the running API has its operation
//   load(body)            take its parts of a loaded request body (a key it leaves out: default)
//   request()             its request body, or null (it has said why it cannot run)
//   words(request)        {busy, failed, cancelled} status words of its run
//   render(last)          draw `last` = {request, response}; returns the idle status words
//   results()             its part of "Results JSON" (null before its first answer)
//   equilibria()          the equilibria it has for Figure 14.5 ({value, label, wing, ...})
//   on                    {event: handler} for announce(event, detail) ("surfaces": a count)

import { state } from "./state.js";

const panels = [];

export function definePanel(panel) {
  if (panels.some((p) => p.name === panel.name)) throw new Error(`two panels named ${panel.name}`);
  panels.push(panel);
  if (panel.operation) state.runs[panel.operation] = 0;
  return panel;
}

/** Every panel, in the order main.js imports them. */
export const allPanels = () => [...panels];

/** The panel that runs `operation`, or null. */
export const panelOf = (operation) => panels.find((p) => p.operation === operation) ?? null;

/** Tell every panel that listens for `event`. */
export function announce(event, detail) {
  for (const panel of panels) panel.on?.[event]?.(detail);
}

/** What tests (and the curious) can read of the panels: each operation's figures. */
export function describe() {
  return Object.fromEntries(panels.filter((p) => p.operation).map((p) => [p.operation, { figures: [...(p.figures ?? [])] }]));
}
