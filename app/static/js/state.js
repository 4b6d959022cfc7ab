// What the page holds between events, in one place: the editor's choices, the fields by key,
// what a loaded body keeps as given, and the runs. Each panel keeps its own last answer
// (`panel.last`, registry.js). Tests read `runs` and `busy` (window.__flexwing.state).

export const state = {
  mode: "planform", // the wing from "planform" numbers or the station "table"
  flightMode: "alpha", // "alpha", "weight" or "lift" (trimmed)
  stiffness: "laws", // "laws" (EI, GJ from the table) or "spar"
  mass: false, // whether the wing carries its mass model (wing.mass, for flutter)
  controls: {}, // field key -> {field, control}: every input rendered from a descriptor
  extra: [], // optional fields this API version has: {field, control}
  // What a loaded body gives that no field shows, sent as given (editor/load.js):
  passThrough: {}, // wing keys
  options: {}, // solver options (the page sets only the safety factor and chordwise panels)
  kept: {}, // top-level keys of the body, sent to each operation whose body has them
  keptFlight: {}, // flight keys the flight panel's mode does not show (a design's fixed alpha)
  runs: { failed: 0 }, // answers per operation (registry.js adds each), and failed runs
  loads: 0, // bodies loaded (editor/load.js), for tests to wait on
  busy: false,
  abort: null, // the running job's AbortController (Cancel)
};
