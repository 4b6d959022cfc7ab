// The loads envelope of a sizing run (POST /loads): along the span the largest and smallest
// shear, bending moment and torque over every case, the case that gives each named on hover;
// and the potato plot, each case's bending moment against its torque at the correlated
// stations, with their convex hull.

import { COLORS, colorOf, draw, line, record } from "./chart.js";
import { namedTooltip } from "./vn.js";

const LOADS = [
  { key: "shear", label: "shear", unit: "N", canvas: "chart-envelope-shear", title: "Shear envelope", color: COLORS.flexible },
  { key: "bending_moment", label: "bending moment", unit: "N·m", canvas: "chart-envelope-moment", title: "Bending moment envelope", color: COLORS.moment },
  { key: "torque", label: "torque", unit: "N·m", canvas: "chart-envelope-torque", title: "Torque envelope", color: COLORS.torque },
];

/** The case named by index `i` of the answer's cases. */
const caseName = (loads, i) => loads.cases[i]?.name ?? `case ${i}`;

/** Envelope along the span and correlated loads of a POST /loads answer with loads
 * (`loads.envelope` not null). */
export function drawEnvelope(loads) {
  const envelope = loads.envelope;
  const series = {};
  const marks = {};
  for (const load of LOADS) {
    const datasets = [];
    for (const [side, dash] of [
      ["max", []],
      ["min", [6, 4]],
    ]) {
      const values = envelope[`${side}_${load.key}`];
      const cases = envelope[`${side}_${load.key}_case`];
      const label = `${side === "max" ? "largest" : "smallest"} ${load.label}`;
      series[`${side}_${load.key}`] = { label, x: envelope.y, y: values };
      const data = envelope.y.map((x, i) => ({ x, y: values[i], name: caseName(loads, cases[i]), status: `${label} ${values[i].toPrecision(4)} ${load.unit}` }));
      datasets.push(line(label, data, load.color, { borderDash: dash, pointRadius: 2, pointHoverRadius: 5 }));
      marks[`root_${side}_${load.key}`] = values[0];
      marks[`root_${side}_${load.key}_case`] = caseName(loads, cases[0]);
    }
    draw(load.canvas, {
      title: `${load.title}: root ${marks[`root_max_${load.key}`].toPrecision(4)} ${load.unit} (${marks[`root_max_${load.key}_case`]})`,
      datasets,
      xTitle: "spanwise position y [m]",
      yTitle: `${load.label} [${load.unit}]`,
      x: { min: 0 },
      plugins: { tooltip: namedTooltip("", "x"), annotations: { hlines: [{ y: 0 }] } },
    });
  }
  const potato = [];
  loads.correlated.forEach((station, s) => {
    const color = colorOf(s);
    const label = `station ${station.station} (y = ${station.y.toFixed(2)} m)`;
    const data = station.cases.map((c, k) => ({ x: station.bending_moment[k], y: station.torque[k], name: caseName(loads, c), status: label }));
    const hull = [...station.hull, station.hull[0]].filter((k) => k !== undefined).map((k) => data[k]);
    series[`correlated_${station.station}`] = { label, x: station.bending_moment, y: station.torque };
    series[`hull_${station.station}`] = { label: `${label}: hull`, x: hull.map((p) => p.x), y: hull.map((p) => p.y) };
    potato.push(line(label, data, color, { showLine: false, pointRadius: 4, pointHoverRadius: 6 }));
    potato.push(line(`${label}: hull`, hull, color, { borderWidth: 1.5, pointRadius: 0, pointHitRadius: 0 }));
  });
  draw("chart-potato", {
    title: "Correlated loads: bending moment against torque (the potato plot)",
    datasets: potato,
    xTitle: "bending moment M [N·m]",
    yTitle: "torque T [N·m]",
    plugins: {
      tooltip: namedTooltip(""),
      legend: { labels: { usePointStyle: true, boxHeight: 10, filter: (item) => !item.text.endsWith(": hull") } },
      annotations: { hlines: [{ y: 0 }], vlines: [{ x: 0, color: COLORS.zero, label: "" }], vlineLabels: false },
    },
  });
  record("envelope", series, marks, { stations: loads.correlated.map((c) => c.station) });
}
