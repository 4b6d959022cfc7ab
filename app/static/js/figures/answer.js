// Any operation's answer, read without knowing it (the generic panel's figure): its numbers as a
// table of paths and values, and its numeric arrays as lines, against `y` where the array's
// object has a `y` of the same length (a spanwise quantity), against `t` or `time` where it has
// those, else against the index.

import { COLORS, draw, line, points, record } from "./chart.js";

const MAX_ITEMS = 20; // items of a list of objects read (a list of cases: the first 20)
const MAX_ROWS = 200; // numbers shown in the table

const isNumbers = (v) => Array.isArray(v) && v.length > 0 && v.every((x) => x === null || typeof x === "number") && v.some((x) => x !== null);
const isObject = (v) => v !== null && typeof v === "object" && !Array.isArray(v);

/** The answer's scalars [{path, value}] and numeric arrays [{path, label, x, y, over}]. */
export function readAnswer(answer) {
  const scalars = [];
  const arrays = [];
  const walk = (node, path, depth) => {
    if (depth > 6) return;
    if (Array.isArray(node)) {
      node.slice(0, MAX_ITEMS).forEach((item, i) => (isObject(item) || Array.isArray(item)) && walk(item, `${path}[${i}]`, depth + 1));
      return;
    }
    const axis = ["y", "t", "time"].find((key) => isNumbers(node[key]));
    for (const [key, value] of Object.entries(node)) {
      const at = path ? `${path}.${key}` : key;
      if (isNumbers(value)) {
        const against = axis && key !== axis && node[axis].length === value.length ? axis : null;
        if (key === axis && Object.values(node).some((v) => v !== value && isNumbers(v) && v.length === value.length)) continue;
        arrays.push({ path: at, x: against ? node[against] : value.map((_, i) => i), y: value, over: against ?? "index" });
      } else if (isObject(value) || Array.isArray(value)) {
        walk(value, at, depth + 1);
      } else if (value !== null) {
        scalars.push({ path: at, value });
      }
    }
  };
  if (isObject(answer)) walk(answer, "", 0);
  // Spanwise quantities first: what the select shows first, and what is drawn.
  arrays.sort((a, b) => Number(b.over === "y") - Number(a.over === "y"));
  return { scalars: scalars.slice(0, MAX_ROWS), arrays };
}

const AXIS = { y: "spanwise position y [m]", t: "time t [s]", time: "time [s]", index: "index" };

/** Draw the array `chosen` (a path) of the answer read by readAnswer on canvas `canvas`; record
 * every array (and, without any, the numbers against their row) as figure `id`'s series. */
export function drawAnswer(id, canvas, { scalars, arrays }, chosen) {
  const shown = arrays.find((a) => a.path === chosen) ?? arrays[0];
  const numbers = scalars.filter((s) => typeof s.value === "number");
  const series = Object.fromEntries(arrays.map((a) => [a.path, { label: a.path, x: a.x, y: a.y }]));
  if (!arrays.length) series.numbers = { label: "the answer's numbers", x: numbers.map((_, i) => i), y: numbers.map((s) => s.value) };
  const drawn = shown ?? { path: "the answer's numbers", ...series.numbers, over: "index" };
  draw(canvas, {
    title: drawn.path,
    datasets: [line(drawn.path, points(drawn.x, drawn.y), COLORS.flexible, { pointRadius: drawn.x.length > 60 ? 0 : 2 })],
    xTitle: AXIS[drawn.over] ?? drawn.over,
    yTitle: drawn.path.split(".").at(-1),
    legend: false,
    plugins: { annotations: { hlines: [{ y: 0 }] } },
  });
  record(id, series, { drawn: drawn.path }, { over: drawn.over });
}
