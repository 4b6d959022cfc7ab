// The V-n diagrams of a sizing run (POST /loads): each diagram's boundary (a weight at an
// altitude) with its named points (A+, C+, D-, the gust points), and every case flown as a point
// at its equivalent airspeed and load factor, its name on hover.

import { COLORS, colorOf, draw, line, record } from "./chart.js";

/** A case's point, hollow when it has no loads. */
const casePoint = (c) => ({ x: c.equivalent_airspeed, y: c.load_factor, name: c.name, status: c.status });

/** Tooltips that name the case under the pointer (`mode` "x": every point at its station). */
export const namedTooltip = (unit, mode = "nearest") => ({
  intersect: mode === "nearest",
  mode,
  callbacks: {
    label: (context) => {
      const { raw } = context;
      const value = `${context.dataset.label}: ${raw.x.toPrecision(4)}, ${raw.y.toPrecision(4)}${unit}`;
      return raw.name ? `${raw.name} (${raw.status ?? value})` : value;
    },
  },
});

/** V-n boundaries, their named points and the cases flown, of a POST /loads answer. */
export function drawVn(loads) {
  const series = {};
  const datasets = [];
  const labels = [];
  loads.vn.forEach((diagram, i) => {
    const label = `${diagram.weight} N at ${diagram.altitude} m`;
    series[`boundary_${i}`] = { label, x: diagram.airspeed, y: diagram.load_factor };
    series[`points_${i}`] = { label: `${label}: named points`, x: diagram.point_airspeed, y: diagram.point_load_factor };
    datasets.push(line(label, diagram.airspeed.map((x, k) => ({ x, y: diagram.load_factor[k] })), colorOf(i)));
    diagram.points.forEach((name, k) => {
      if (i === 0) labels.push({ x: diagram.point_airspeed[k], y: diagram.point_load_factor[k], text: name, dx: 4, dy: -9, color: colorOf(i) });
    });
  });
  const flown = loads.cases.filter((c) => c.status === "equilibrium").map(casePoint);
  const lost = loads.cases.filter((c) => c.status !== "equilibrium" && c.equivalent_airspeed > 0).map(casePoint);
  series.cases = { label: "cases with loads", x: flown.map((p) => p.x), y: flown.map((p) => p.y) };
  series.cases_without_loads = { label: "cases without loads", x: lost.map((p) => p.x), y: lost.map((p) => p.y) };
  const point = { showLine: false, pointRadius: 5, pointHoverRadius: 7, borderWidth: 1.5 };
  datasets.push(line("cases with loads", flown, "#222", { ...point, pointStyle: "circle", backgroundColor: "rgba(34, 34, 34, 0.35)" }));
  if (lost.length) datasets.push(line("cases without loads", lost, COLORS.beyond, { ...point, pointStyle: "crossRot", pointRadius: 7 }));
  draw("chart-vn", {
    title: loads.vn.length ? "V-n diagrams and the cases flown" : "The cases flown",
    datasets,
    xTitle: "equivalent airspeed [m/s]",
    yTitle: "load factor n [-]",
    x: { min: 0 },
    pointLegend: true,
    plugins: { tooltip: namedTooltip(""), annotations: { labels, hlines: [{ y: 0, color: "#555" }] } },
  });
  record(
    "vn",
    series,
    { diagrams: loads.vn.length, cases: loads.cases.length, answered: loads.info.answered },
    { names: loads.cases.map((c) => c.name), points: loads.vn.map((d) => d.points) },
  );
}
